"""PCD point clouds (ascii, binary, binary_compressed) via pypcd4."""

from __future__ import annotations

import io
import re
from pathlib import Path

import numpy as np

from core.errors import FileFormatError
from core.io.pcd_checks import check_pcd_header
from core.io.problems import unreadable

NORMAL_FIELDS = ("normal_x", "normal_y", "normal_z")


def _unpack_rgb(packed: np.ndarray) -> np.ndarray:
    """(n, 3) uint8 colours from PCL's float- or int-packed 0x00RRGGBB field."""
    raw = np.ascontiguousarray(packed)
    as_int = raw.view(np.uint32) if raw.dtype.itemsize == 4 else raw.astype(np.uint32)
    return np.column_stack([(as_int >> s) & 0xFF for s in (16, 8, 0)]).astype(np.uint8)


def _with_count(path: Path, n_fields: int) -> io.BytesIO:
    """The file with the optional COUNT line (1 per field) that pypcd4 requires added."""
    data = path.read_bytes()
    count = b"COUNT " + b" ".join([b"1"] * n_fields) + b"\n"
    match = re.search(rb"^SIZE[^\n]*\n", data, re.M)
    if match is None:
        raise FileFormatError(f"{path}: bad PCD header (no SIZE line)")
    return io.BytesIO(data[: match.end()] + count + data[match.end() :])


def _load(path: Path, fields: dict[str, list[str]]):
    """pypcd4's PointCloud, with any parser failure as a format error naming the file."""
    from pypcd4 import PointCloud

    try:
        if "COUNT" not in fields:
            return PointCloud.from_fileobj(_with_count(path, len(fields["SIZE"])))
        return PointCloud.from_path(path)
    except Exception as exc:  # pypcd4 raises many types (ValueError, struct.error, lzf...)
        raise unreadable(path, "PCD", exc) from exc


def read_pcd(path: Path, columns=None) -> tuple[np.ndarray, dict[str, np.ndarray], tuple]:
    """(n, 3) xyz and normals/colours/intensity when the PCD has those fields."""
    declared, fields = check_pcd_header(path)
    cloud = _load(path, fields)
    fields = tuple(cloud.fields)
    if not {"x", "y"}.issubset(fields):
        raise FileFormatError(f"{path}: PCD has no x/y fields ({', '.join(fields)})")
    axes = [a for a in ("x", "y", "z") if a in fields]
    try:
        points = cloud.numpy(axes).astype(np.float64)
        attrs: dict[str, np.ndarray] = {}
        if set(NORMAL_FIELDS).issubset(fields):
            attrs["normals"] = cloud.numpy(NORMAL_FIELDS).astype(np.float64)
        for name in ("rgb", "rgba"):
            if name in fields:
                attrs["colors"] = _unpack_rgb(cloud.pc_data[name])
                break
        if "intensity" in fields:
            attrs["intensity"] = cloud.numpy(("intensity",))[:, 0].astype(np.float64)
    except (ValueError, KeyError) as exc:
        raise unreadable(path, "PCD", exc) from exc
    if len(points) != declared:
        raise FileFormatError(f"{path}: truncated PCD (header declares {declared:,} points, "
                              f"{len(points):,} read)")
    return points, attrs, (f"PCD {cloud.metadata.data.value}",)

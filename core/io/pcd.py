"""PCD point clouds (ascii, binary, binary_compressed) via pypcd4."""

from __future__ import annotations

import io
import re
from pathlib import Path

import numpy as np

from core.errors import FileFormatError
from core.io.pcd_checks import check_pcd_header
from core.io.problems import unreadable
from core.io.view_hint import sensor_hint

NORMAL_FIELDS = ("normal_x", "normal_y", "normal_z")


def _unpack_rgb(packed: np.ndarray) -> np.ndarray:
    """(n, 3) uint8 colours from PCL's float- or int-packed 0x00RRGGBB field."""
    raw = np.ascontiguousarray(packed)
    as_int = raw.view(np.uint32) if raw.dtype.itemsize == 4 else raw.astype(np.uint32)
    return np.column_stack([(as_int >> s) & 0xFF for s in (16, 8, 0)]).astype(np.uint8)


def _normalized(path: Path, fields: dict[str, list[str]]) -> io.BytesIO | None:
    """The file with what pypcd4 requires of a header and older files lack: the optional COUNT
    line (1 per field) and VERSION 0.7 for the v.5/v.6 headers (same data layout); None when
    the file needs neither."""
    version = (fields.get("VERSION") or [""])[0]
    if "COUNT" in fields and version in ("0.7", ".7"):
        return None
    data = path.read_bytes()
    if "COUNT" not in fields:
        count = b"COUNT " + b" ".join([b"1"] * len(fields["SIZE"])) + b"\n"
        match = re.search(rb"^SIZE[^\n]*\n", data, re.M)
        if match is None:
            raise FileFormatError(f"{path}: bad PCD header (no SIZE line)")
        data = data[: match.end()] + count + data[match.end() :]
    data = re.sub(rb"^VERSION[^\n]*", b"VERSION 0.7", data, count=1, flags=re.M)
    return io.BytesIO(data)


def _load(path: Path, fields: dict[str, list[str]]):
    """pypcd4's PointCloud, with any parser failure as a format error naming the file."""
    from pypcd4 import PointCloud

    try:
        fixed = _normalized(path, fields)
        return PointCloud.from_path(path) if fixed is None else PointCloud.from_fileobj(fixed)
    except Exception as exc:  # pypcd4 raises many types (ValueError, struct.error, lzf...)
        raise unreadable(path, "PCD", exc) from exc


def read_pcd(path: Path, columns=None) -> tuple[np.ndarray, dict[str, np.ndarray], tuple]:
    """(n, 3) xyz and normals/colours/intensity when the PCD has those fields."""
    declared, fields = check_pcd_header(path)
    cloud = _load(path, fields)
    real = {f.lower(): f for f in reversed(cloud.fields)}  # 'X' (PDAL) is 'x'; first one wins
    if not {"x", "y"}.issubset(real):
        raise FileFormatError(f"{path}: PCD has no x/y fields ({', '.join(cloud.fields)})")
    axes = [real[a] for a in ("x", "y", "z") if a in real]
    try:
        points = cloud.numpy(axes).astype(np.float64)
        attrs: dict[str, np.ndarray] = {}
        if set(NORMAL_FIELDS).issubset(real):
            attrs["normals"] = cloud.numpy([real[n] for n in NORMAL_FIELDS]).astype(np.float64)
        for name in ("rgb", "rgba"):
            if name in real:
                attrs["colors"] = _unpack_rgb(cloud.pc_data[real[name]])
                break
        if "intensity" in real:
            attrs["intensity"] = cloud.numpy((real["intensity"],))[:, 0].astype(np.float64)
    except (ValueError, KeyError) as exc:
        raise unreadable(path, "PCD", exc) from exc
    if len(points) != declared:
        raise FileFormatError(f"{path}: truncated PCD (header declares {declared:,} points, "
                              f"{len(points):,} read)")
    hint = sensor_hint(fields.get("VIEWPOINT"))
    return points, attrs, (f"PCD {cloud.metadata.data.value}", *([hint] if hint else []))

"""PCD point clouds (ascii, binary, binary_compressed) via pypcd4."""

from __future__ import annotations

import io
import os
import re
from pathlib import Path

import numpy as np

from core.errors import FileFormatError

NORMAL_FIELDS = ("normal_x", "normal_y", "normal_z")


def _unpack_rgb(packed: np.ndarray) -> np.ndarray:
    """(n, 3) uint8 colours from PCL's float- or int-packed 0x00RRGGBB field."""
    raw = np.ascontiguousarray(packed)
    as_int = raw.view(np.uint32) if raw.dtype.itemsize == 4 else raw.astype(np.uint32)
    return np.column_stack([(as_int >> s) & 0xFF for s in (16, 8, 0)]).astype(np.uint8)


MAX_LZF_RATIO = 200  # a compressed body claiming more than this expansion is bogus
HEADER_LINES = 20


def _check_size(path: Path) -> dict[str, list[str]]:
    """Refuse headers whose POINTS x row size the body cannot hold (before any allocation);
    returns the header's fields (upper-case keyword -> words)."""
    fields: dict[str, list[str]] = {}
    with open(path, "rb") as fh:
        for _ in range(HEADER_LINES):
            words = fh.readline().decode("ascii", "replace").split()
            if words and not words[0].startswith("#"):
                fields[words[0].upper()] = words[1:]
            if words and words[0].upper() == "DATA":
                break
        body = os.fstat(fh.fileno()).st_size - fh.tell()
    try:
        n = int(fields["POINTS"][0])
        row = sum(int(s) * int(c) for s, c in zip(fields["SIZE"], fields.get(
            "COUNT", ["1"] * len(fields["SIZE"])), strict=False))
        kind = fields["DATA"][0].lower()
    except (KeyError, IndexError, ValueError):
        raise FileFormatError(f"{path}: bad PCD header (POINTS, SIZE or DATA missing)") from None
    limit = {"binary": body, "binary_compressed": body * MAX_LZF_RATIO}.get(kind, body * 64)
    if n * row > limit or n < 0:
        raise FileFormatError(f"{path}: truncated PCD (header claims {n:,} points, "
                              f"the file holds {body:,} bytes of data)")
    return fields


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
        raise FileFormatError(f"{path}: unreadable PCD ({type(exc).__name__}: {exc})") from None


def read_pcd(path: Path, columns=None) -> tuple[np.ndarray, dict[str, np.ndarray], tuple]:
    """(n, 3) xyz and normals/colours/intensity when the PCD has those fields."""
    cloud = _load(path, _check_size(path))
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
        raise FileFormatError(f"{path}: bad PCD fields ({exc})") from None
    return points, attrs, (f"PCD {cloud.metadata.data.value}",)

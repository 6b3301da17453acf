"""LAS/LAZ LiDAR via laspy (lazrs backend for LAZ), with scale and offset applied."""

from __future__ import annotations

import os
import struct
from pathlib import Path

import numpy as np

from core.errors import FileFormatError

MAX_LAZ_RATIO = 200  # a LAZ header claiming more than this many raw bytes per file byte is bogus


def _check_header(path: Path) -> None:
    """Sanity-check the public header block before laspy trusts its counts and offsets.

    A corrupt VLR count or offset can make a reader loop or allocate without bound; the
    fields checked are at fixed offsets in every LAS 1.0-1.4 header.
    """
    size = os.path.getsize(path)
    with open(path, "rb") as fh:
        head = fh.read(375)
    if len(head) < 227 or head[:4] != b"LASF":
        raise FileFormatError(f"{path}: not a LAS/LAZ file (no LASF header)")
    header_size, offset, n_vlrs = struct.unpack_from("<HII", head, 94)
    fmt, record, legacy = struct.unpack_from("<BHI", head, 104)
    count = legacy
    if head[25] >= 4 and len(head) >= 255:
        count = max(count, struct.unpack_from("<Q", head, 247)[0])
        first_evlr, n_evlrs = struct.unpack_from("<QI", head, 235)
        if n_evlrs and (first_evlr > size or n_evlrs * 60 > size - first_evlr):
            raise FileFormatError(f"{path}: corrupt LAS header (extended VLRs past the end)")
    if not 227 <= header_size <= offset <= size or n_vlrs * 54 > offset - header_size:
        raise FileFormatError(f"{path}: corrupt LAS header (sizes and offsets disagree)")
    compressed = bool(fmt & 0xC0)
    limit = (size - offset) * (MAX_LAZ_RATIO if compressed else 1)
    if count * record > limit:
        raise FileFormatError(f"{path}: truncated LAS/LAZ (header claims {count:,} points, "
                              f"file has {size:,} bytes)")
    if compressed:
        _check_chunk_table(path, offset, count, size)


def _check_chunk_table(path: Path, offset: int, count: int, size: int) -> None:
    """A LAZ chunk table must fit the file and list at most one chunk per point.

    lazrs allocates the table from its stored length, and a failed allocation aborts the
    whole process (a Rust panic), so a corrupt length must never reach it.
    """
    with open(path, "rb") as fh:
        fh.seek(offset)
        raw = fh.read(8)
        table = struct.unpack("<q", raw)[0] if len(raw) == 8 else -2
        if table == -1:
            return  # written without a chunk table (streaming); laspy copes
        if not offset + 8 <= table <= size - 8:
            raise FileFormatError(f"{path}: corrupt LAZ (chunk table outside the file)")
        fh.seek(table)
        version, n_chunks = struct.unpack("<II", fh.read(8))
    if version != 0 or n_chunks > count + 1:
        raise FileFormatError(f"{path}: corrupt LAZ chunk table ({n_chunks:,} chunks for "
                              f"{count:,} points)")


def _open(path: Path):
    """laspy reader object; errors become format errors naming the file."""
    import laspy

    try:
        return laspy.open(str(path))
    except Exception as exc:  # laspy raises LaspyException, ValueError, OSError...
        raise FileFormatError(f"{path}: not a readable LAS/LAZ file ({exc})") from None


def _check_size(header, path: Path) -> None:
    """Refuse point counts the file cannot hold, before laspy allocates for them."""
    size = os.path.getsize(path)
    raw = header.point_count * header.point_format.size
    limit = size * MAX_LAZ_RATIO if header.are_points_compressed else size
    if raw > limit:
        raise FileFormatError(f"{path}: truncated LAS/LAZ (header claims "
                              f"{header.point_count:,} points, file has {size:,} bytes)")


def _colors(las) -> np.ndarray | None:
    """(n, 3) uint8 RGB, or None when the format has no colour or every colour is 0."""
    names = set(las.point_format.dimension_names)
    if not {"red", "green", "blue"}.issubset(names):
        return None
    rgb = np.column_stack([np.asarray(las[c]) for c in ("red", "green", "blue")])
    if not rgb.any():
        return None
    return (rgb >> 8 if rgb.max() > 255 else rgb).astype(np.uint8)


def read_las(path: Path, columns=None) -> tuple[np.ndarray, dict[str, np.ndarray], tuple]:
    """(n, 3) scaled coordinates plus colours, intensity and classification."""
    _check_header(path)
    with _open(path) as reader:
        _check_size(reader.header, path)
        try:
            las = reader.read()
        except Exception as exc:  # truncated or corrupt point records
            raise FileFormatError(f"{path}: bad LAS/LAZ point data ({exc})") from None
    points = np.column_stack([np.asarray(las.x), np.asarray(las.y), np.asarray(las.z)])
    attrs: dict[str, np.ndarray] = {
        "intensity": np.asarray(las.intensity, dtype=np.float64),
        "classification": np.asarray(las.classification, dtype=np.uint8),
    }
    colors = _colors(las)
    if colors is not None:
        attrs["colors"] = colors
    version = f"LAS {las.header.version}, point format {las.header.point_format.id}"
    return points.astype(np.float64), attrs, (version,)

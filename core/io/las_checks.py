"""Sanity checks of LAS/LAZ headers before laspy and lazrs trust their counts and offsets.

Fuzzing showed why: a corrupt VLR count made laspy loop, and corrupt LASzip chunk fields made
lazrs allocate gigabytes, which aborts the whole process (a Rust panic) instead of raising.
Only fields at fixed offsets of the LAS 1.0-1.4 and LASzip specifications are read.
"""

from __future__ import annotations

import os
import struct
from pathlib import Path

from core.errors import FileFormatError

VARIABLE_CHUNKS = 0xFFFFFFFF
MAX_CHUNK_POINTS = 1_000_000  # lazrs allocates a whole chunk up front; writers use 50,000
MAX_LAZ_RATIO = 200  # a LAZ header claiming more than this many raw bytes per file byte is bogus


def check_las_file(path: Path) -> None:
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
        _check_laszip_vlr(path, count, header_size, n_vlrs, size)
        _check_chunk_table(path, offset, count, size)


def _check_laszip_vlr(path: Path, count: int, start: int, n_vlrs: int, size: int) -> None:
    """The LASzip VLR's special-EVLR count and item list must be plausible (lazrs trusts them)."""
    with open(path, "rb") as fh:
        fh.seek(start)
        for _ in range(n_vlrs):
            vlr = fh.read(54)
            if len(vlr) < 54:
                break
            user, record_id, length = vlr[2:18].rstrip(b"\0"), *struct.unpack_from("<HH", vlr, 18)
            data = fh.read(length)
            if user == b"laszip encoded" and record_id == 22204:
                if len(data) < 34:
                    break
                chunk = struct.unpack_from("<I", data, 12)[0]
                n_special, special_at, n_items = struct.unpack_from("<qqH", data, 16)
                bad_chunk = chunk != VARIABLE_CHUNKS and chunk > max(count, MAX_CHUNK_POINTS)
                bad_special = n_special not in (-1, 0) and not (
                    0 < n_special * 60 <= size - special_at)
                if bad_chunk or bad_special or len(data) < 34 + 6 * n_items:
                    break
                return
    raise FileFormatError(f"{path}: corrupt LAZ (missing or damaged LASzip record)")


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

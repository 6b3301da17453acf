"""PCD headers checked before pypcd4 trusts them: a bounded header, and declared sizes that
the file (or, for compressed data, the memory available) can hold."""

from __future__ import annotations

import os
import struct
from pathlib import Path

from core.errors import FileFormatError
from core.io.precheck import check_text
from core.io.sizes import check_memory

MAX_HEADER_BYTES = 1 << 16  # a PCD header is a few hundred bytes: give up well before data
MAX_LZF_RATIO = 200  # LZF expands at most about 90 times (a 3-byte back-reference, 264 bytes)
MIN_ASCII_VALUE_BYTES = 2  # an ascii value is at least one character and a separator


def _header(path: Path) -> tuple[dict[str, list[str]], int, int]:
    """(keyword -> words, header bytes, file size), reading at most MAX_HEADER_BYTES."""
    with open(path, "rb") as fh:
        head = fh.read(MAX_HEADER_BYTES)
        size = os.fstat(fh.fileno()).st_size
    fields: dict[str, list[str]] = {}
    pos = 0
    while True:
        end = head.find(b"\n", pos)
        if end < 0:
            raise FileFormatError(f"{path}: not a PCD file: no DATA line in its first "
                                  f"{MAX_HEADER_BYTES // 1024} KB")
        words = head[pos:end].decode("ascii", "replace").split()
        pos = end + 1
        if words and not words[0].startswith("#"):
            fields[words[0].upper()] = words[1:]
            if words[0].upper() == "DATA":
                return fields, pos, size


def _counts(fields: dict[str, list[str]], path: Path) -> tuple[int, int, int, str]:
    """(points, bytes per point, values per point, data kind) from the header fields."""
    try:
        n = int(fields["POINTS"][0])
        sizes = [int(s) for s in fields["SIZE"]]
        counts = [int(c) for c in fields.get("COUNT", ["1"] * len(sizes))]
        kind = fields["DATA"][0].lower()
    except (KeyError, IndexError, ValueError):
        raise FileFormatError(f"{path}: bad PCD header (POINTS, SIZE or DATA missing or not "
                              "whole numbers)") from None
    if n < 0 or min(sizes + counts, default=0) < 1 or len(counts) != len(sizes):
        raise FileFormatError(f"{path}: bad PCD header (negative or mismatched counts)")
    return n, sum(s * c for s, c in zip(sizes, counts, strict=True)), sum(counts), kind


def check_pcd_header(path: Path) -> tuple[int, dict[str, list[str]]]:
    """(points declared, header fields: upper-case keyword -> words), once the sizes the
    header implies are plausible."""
    fields, start, size = _header(path)
    n, row, values, kind = _counts(fields, path)
    body = size - start
    if kind == "binary_compressed":
        with open(path, "rb") as fh:
            fh.seek(start)
            raw = fh.read(8)
        if len(raw) < 8:
            raise FileFormatError(f"{path}: truncated PCD (no compressed block)")
        packed, unpacked = struct.unpack("<II", raw)
        if packed > body - 8 or unpacked < n * row or unpacked > packed * MAX_LZF_RATIO:
            raise FileFormatError(f"{path}: corrupt PCD (the compressed block of {packed:,} "
                                  f"bytes claims {unpacked:,} bytes for {n:,} points; the file "
                                  f"holds {body:,})")
        check_memory(path, unpacked, "the compressed PCD data")
        return n, fields
    if kind == "ascii":
        check_text(path, "PCD", start)
    need = n * (row if kind == "binary" else values * MIN_ASCII_VALUE_BYTES)
    if need > body:
        raise FileFormatError(f"{path}: truncated PCD (header declares {n:,} points, the "
                              f"file holds {body:,} bytes of data)")
    return n, fields

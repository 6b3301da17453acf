"""Sizes a file declares, checked before anything is allocated for them.

A header is a promise: a corrupt or hostile one can claim gigabytes in a file of a few bytes,
and compressed data can honestly expand a thousandfold. Declared sizes are checked against
what the file holds and, for compressed data, against the memory available.
"""

from __future__ import annotations

import os
import zipfile
from pathlib import Path

import numpy as np

from core.errors import FileFormatError
from core.storage.memory import available_memory

MEMORY_FRACTION = 0.5  # compressed data may expand to at most this share of available memory
MAX_DEFLATE_RATIO = 1032  # deflate cannot expand more than this (RFC 1951's longest match)


def _gb(nbytes: int) -> str:
    return f"{nbytes / 1e9:.3g} GB"


def check_memory(path: Path, nbytes: int, what: str) -> None:
    """Refuse `what` (e.g. 'the array 'points'') if expanding it needs too much memory."""
    avail = available_memory()
    if nbytes > MEMORY_FRACTION * avail:
        raise FileFormatError(f"{path}: {what} would need {_gb(nbytes)} of memory once "
                              f"decompressed; only {_gb(avail)} is available")


def _npy_header(fh) -> tuple[int, int]:
    """(declared data bytes, header bytes) of the .npy stream at `fh`'s position."""
    start = fh.tell() if fh.seekable() else 0
    version = np.lib.format.read_magic(fh)
    read = {(1, 0): np.lib.format.read_array_header_1_0,
            (2, 0): np.lib.format.read_array_header_2_0}.get(version)
    if read is None:
        raise ValueError(f"unsupported .npy version {version}")
    shape, _, dtype = read(fh)
    count = 1
    for n in shape:
        count *= int(n)
    used = fh.tell() - start if fh.seekable() else 0
    return count * dtype.itemsize, used


def check_npy(path: Path, fh) -> None:
    """A plain .npy: the declared array must fit in the file (then rewinds `fh`)."""
    nbytes, header = _npy_header(fh)
    body = os.fstat(fh.fileno()).st_size - header
    fh.seek(0)
    if nbytes > body:
        raise FileFormatError(f"{path}: truncated NumPy file (its header declares "
                              f"{nbytes:,} bytes of data, the file holds {body:,})")


def check_npz_member(path: Path, archive: zipfile.ZipFile, key: str) -> None:
    """An .npz member: its declared array must agree with the zip's sizes and fit in memory."""
    name = key if key in archive.namelist() else f"{key}.npy"
    info = archive.getinfo(name)
    with archive.open(info) as member:
        nbytes, header = _npy_header(member)
    stored = info.compress_type == zipfile.ZIP_STORED
    holds = info.file_size - header
    if nbytes > holds or (not stored and info.file_size > info.compress_size * MAX_DEFLATE_RATIO
                          + 1024):
        raise FileFormatError(f"{path}: corrupt NumPy archive (array {key!r} declares "
                              f"{nbytes:,} bytes, its zip entry holds {max(holds, 0):,})")
    if not stored:
        check_memory(path, nbytes, f"the array {key!r}")


def check_npz_archive(path: Path, archive: zipfile.ZipFile, keys: list[str]) -> None:
    """The archive's members do not overlap (a zip bomb), and the arrays `keys` to be read
    each pass check_npz_member and together fit in memory (as float64 coordinates too)."""
    infos = archive.infolist()
    if sum(info.compress_size for info in infos) > os.fstat(archive.fp.fileno()).st_size:
        raise FileFormatError(f"{path}: corrupt NumPy archive (its members overlap)")
    total = 0
    for key in dict.fromkeys(keys):
        check_npz_member(path, archive, key)
        name = key if key in archive.namelist() else f"{key}.npy"
        total += archive.getinfo(name).file_size
    check_memory(path, total, f"the arrays {', '.join(dict.fromkeys(keys))}")

"""Read .npz archives without trusting them: declared array sizes are checked against the
bytes the archive really holds before anything is allocated, and pickles are never loaded.

A header that claims 10^10 rows in a 100 KB file is a FileFormatError at once, not a
MemoryError (or minutes of swapping) on every run.
"""

from __future__ import annotations

import math
import os
import struct
import zipfile
import zlib
from dataclasses import dataclass
from pathlib import Path
from typing import BinaryIO

import numpy as np

from core.errors import FileFormatError
from core.storage.memory import available_memory

MAX_DEFLATE_RATIO = 1100  # deflate expands at most ~1032:1; beyond that a size is a lie
_LOCAL_HEADER = struct.Struct("<4s5H3L2H")  # a zip member's local header (30 bytes)
_HEADER_READERS = {(1, 0): np.lib.format.read_array_header_1_0,
                   (2, 0): np.lib.format.read_array_header_2_0}


def _bad(path: Path, problem: str) -> FileFormatError:
    return FileFormatError(f"{path}: not a readable .npz table ({problem})")


def _check_member(zf: zipfile.ZipFile, info: zipfile.ZipInfo, archive_bytes: int,
                  path: Path) -> _Member:
    """The member's .npy header declares exactly the bytes the member holds; what it
    declares."""
    name = info.filename
    if info.compress_size > archive_bytes:
        raise _bad(path, f"{name} claims more bytes than the file has")
    if info.file_size > MAX_DEFLATE_RATIO * info.compress_size + 4096:
        raise _bad(path, f"{name} claims {info.file_size:,} bytes from {info.compress_size:,}")
    with zf.open(info) as fh:
        version = np.lib.format.read_magic(fh)
        if version not in _HEADER_READERS:
            raise _bad(path, f"{name}: unsupported .npy version {version}")
        shape, fortran, dtype = _HEADER_READERS[version](fh)
        header_bytes = fh.tell()
    if dtype.hasobject:
        raise _bad(path, f"{name} holds Python objects (pickles are never loaded)")
    data_bytes = math.prod(shape) * dtype.itemsize
    if header_bytes + data_bytes != info.file_size:
        raise _bad(path, f"{name} declares shape {shape} ({data_bytes:,} bytes) but holds "
                         f"{max(info.file_size - header_bytes, 0):,}")
    return _Member(info, shape, fortran, dtype, header_bytes)


def _check_total(members: list[_Member], archive_bytes: int, path: Path) -> None:
    """The members hold no more bytes than the file (members that overlap are a zip bomb:
    each within its ratio, together thousands of times the file), and their arrays fit in
    the memory this process may still take."""
    if sum(m.info.compress_size for m in members) > archive_bytes:
        raise _bad(path, "its members overlap")
    total = sum(m.info.file_size for m in members)
    room = available_memory()
    if total > room:
        raise _bad(path, f"its arrays would take {total / 1e9:.3g} GB of memory; "
                         f"{room / 1e9:.3g} GB is available")


@dataclass(frozen=True)
class _Member:
    """An archive member and what its .npy header declares."""

    info: zipfile.ZipInfo
    shape: tuple[int, ...]
    fortran: bool
    dtype: np.dtype
    header_bytes: int

    @property
    def name(self) -> str:
        """The array's name (np.load's: the member's without '.npy')."""
        return self.info.filename.removesuffix(".npy")


def _data_offset(fh: BinaryIO, member: _Member, path: Path) -> int:
    """Where an uncompressed member's .npy bytes (its header first) start in the file."""
    fh.seek(member.info.header_offset)
    local = fh.read(_LOCAL_HEADER.size)
    if len(local) != _LOCAL_HEADER.size or local[:4] != b"PK\x03\x04":
        raise _bad(path, f"{member.info.filename}: bad local header")
    name_bytes, extra_bytes = _LOCAL_HEADER.unpack(local)[-2:]
    return member.info.header_offset + len(local) + name_bytes + extra_bytes


def _read_stored(fh: BinaryIO, member: _Member, path: Path, check_crc: bool) -> np.ndarray:
    """An uncompressed member's array read straight from the file (one copy); with
    `check_crc`, one CRC-32 pass over its bytes compared with the zip's, as zipfile does while
    it reads, without its many small copies."""
    start = _data_offset(fh, member, path)
    shape = member.shape[::-1] if member.fortran else member.shape
    out = np.empty(shape, dtype=member.dtype)
    fh.seek(start)
    header = fh.read(member.header_bytes)
    data = out.reshape(-1).view(np.uint8)
    if len(header) != member.header_bytes or (
            out.nbytes and fh.readinto(data) != out.nbytes):
        raise _bad(path, f"{member.info.filename} is cut short")
    if check_crc and zlib.crc32(data, zlib.crc32(header)) != member.info.CRC:
        raise _bad(path, f"Bad CRC-32 for file {member.info.filename!r}")
    return out.T if member.fortran else out


class Arrays(dict):
    """An archive's arrays by name; `crcs`: the CRC-32 the archive records for each member
    (by member name, "points.npy"), checked against the bytes read unless the read was
    trusted (core.storage.checksums compares them with the ones written last)."""

    crcs: dict[str, int]


def read_npz(path: str | os.PathLike, *, trusted: bool = False) -> Arrays:
    """Every array of the archive at `path` by name, after checking the declared sizes.

    FileFormatError (naming the file) for a missing, broken or lying archive. Uncompressed
    members (what this program writes) are read straight into their arrays and their
    CRC-32s compared with the zip's; `trusted`: a file this program wrote a moment ago,
    read without that CRC pass (the same arrays, in about half the time); never for a file
    that waited on disk. The arrays are the process's own, never views of the file (one cut
    in place later would be a bus error where they are read).
    """
    path = Path(path)
    try:  # our own handle: np.load leaks the one it opens when the zip is broken
        with open(path, "rb") as fh:
            archive_bytes = os.fstat(fh.fileno()).st_size
            with zipfile.ZipFile(fh) as zf:
                members = [_check_member(zf, info, archive_bytes, path)
                           for info in zf.infolist()]
            _check_total(members, archive_bytes, path)
            out = Arrays()
            out.crcs = {m.info.filename: m.info.CRC for m in members}
            if all(m.info.compress_type == zipfile.ZIP_STORED
                   and m.info.compress_size == m.info.file_size for m in members):
                out.update((m.name, _read_stored(fh, m, path, not trusted)) for m in members)
                return out
            fh.seek(0)
            data = np.load(fh, allow_pickle=False)
            if not isinstance(data, np.lib.npyio.NpzFile):
                raise ValueError("a single array, not an archive")
            with data:
                out.update((name, data[name]) for name in data.files)
            return out
    except FileNotFoundError:
        raise FileFormatError(f"{path}: no such file") from None
    except MemoryError:
        raise _bad(path, "too large to read into the memory available") from None
    except FileFormatError:
        raise
    except (OSError, ValueError, EOFError, zipfile.BadZipFile, KeyError, SyntaxError,
            NotImplementedError, RuntimeError, zlib.error) as exc:  # RuntimeError: encrypted
        raise _bad(path, str(exc).splitlines()[0] if str(exc) else type(exc).__name__) from None

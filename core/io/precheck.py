"""Cheap checks of a file's bytes before a third-party parser sees them.

Text formats must hold no NUL bytes (binary data, or a damaged or sparse file whose holes
would otherwise be parsed as gigabytes of text); binary STL and GLB must be as long as their
headers say; a VTU must end with its closing tag. Each check reads the file in bounded chunks
and allocates nothing big.
"""

from __future__ import annotations

import os
import struct
from pathlib import Path

from core.errors import FileFormatError

CHUNK = 1 << 20
TEXT_FORMATS = {".xyz", ".pts", ".txt", ".csv", ".obj", ".off", ".gltf"}
STL_HEADER, STL_TRIANGLE = 84, 50
VTU_TAIL = 4096  # bytes read from a VTU's end to find its closing tag


def first_nul(path: Path, start: int = 0) -> int | None:
    """Offset of the first NUL byte at or after `start`, or None."""
    with open(path, "rb") as fh:
        fh.seek(start)
        pos = start
        while chunk := fh.read(CHUNK):
            at = chunk.find(b"\0")
            if at >= 0:
                return pos + at
            pos += len(chunk)
    return None


def check_text(path: Path, what: str, start: int = 0) -> None:
    """Refuse a text file holding NUL bytes, saying where."""
    at = first_nul(path, start)
    if at is not None:
        raise FileFormatError(f"{path}: not a text {what} file: it holds binary (NUL) bytes "
                              f"from byte {at:,} (binary data, or a damaged or sparse file)")


def _head(path: Path, n: int) -> bytes:
    with open(path, "rb") as fh:
        return fh.read(n)


def _check_stl(path: Path, size: int) -> None:
    """A binary STL is exactly 84 + 50 n bytes; anything else must be ascii text."""
    head = _head(path, STL_HEADER)
    if len(head) == STL_HEADER:
        (n,) = struct.unpack_from("<I", head, 80)
        if size == STL_HEADER + STL_TRIANGLE * n:
            return
    if first_nul(path) is not None:
        n_text = f"{n:,}" if len(head) == STL_HEADER else "no"
        raise FileFormatError(f"{path}: not a valid STL file: binary, but its size ({size:,} "
                              f"bytes) does not match the {n_text} triangles its header "
                              "declares")


def _check_glb(path: Path, size: int) -> None:
    """GLB: 'glTF' magic, version 2, total length = file size, chunks inside the file."""
    head = _head(path, 20)
    if len(head) < 20 or head[:4] != b"glTF":
        raise FileFormatError(f"{path}: not a GLB file: it does not start with 'glTF'")
    version, length, chunk, kind = struct.unpack_from("<III4s", head, 4)
    if version != 2 or length != size or 20 + chunk > size or kind != b"JSON":
        raise FileFormatError(f"{path}: corrupt GLB header (version {version}, length "
                              f"{length:,} for a file of {size:,} bytes, JSON chunk of "
                              f"{chunk:,} bytes)")


def _check_vtk(path: Path) -> None:
    """Legacy VTK: its third line says ASCII or BINARY; ASCII bodies must be text."""
    lines = _head(path, 1024).split(b"\n", 3)
    if len(lines) > 2 and lines[2].strip().upper() == b"ASCII":
        check_text(path, "VTK")


def _check_ply(path: Path) -> None:
    """ASCII PLY must be text throughout."""
    if b"format ascii" in _head(path, 512):
        check_text(path, "PLY")


def _check_vtu(path: Path, size: int) -> None:
    """VTK XML: the file ends with </VTKFile> (a cut file, or one padded with gigabytes of
    zeros, is refused before any parser reads it), and its XML up to any raw appended data
    holds no NUL byte."""
    with open(path, "rb") as fh:
        fh.seek(max(size - VTU_TAIL, 0))
        tail = fh.read().rstrip(b" \t\r\n\0")
    if not tail.endswith(b"</VTKFile>"):
        padded = " (it ends in NUL bytes: padded or sparse)" if size and _last_byte(path) == 0 \
            else ""
        raise FileFormatError(f"{path}: not a complete VTU file: it does not end with "
                              f"</VTKFile>{padded}")
    at = first_nul(path)
    if at is not None and at < _appended_at(path, at):
        raise FileFormatError(f"{path}: not a valid VTU file: its XML holds binary (NUL) "
                              f"bytes from byte {at:,}")


def _last_byte(path: Path) -> int:
    with open(path, "rb") as fh:
        fh.seek(-1, os.SEEK_END)
        return fh.read(1)[0]


def _appended_at(path: Path, limit: int) -> int:
    """Offset of '<AppendedData' within the first `limit` bytes (+ its length), or `limit`
    + 1 when it is not there (NUL bytes are then inside the XML)."""
    marker = b"<AppendedData"
    with open(path, "rb") as fh:
        pos, carry = 0, b""
        while pos < limit + len(marker) and (chunk := fh.read(CHUNK)):
            at = (carry + chunk).find(marker)
            if at >= 0:
                return pos - len(carry) + at
            carry = (carry + chunk)[-len(marker):]
            pos += len(chunk)
    return limit + 1


def precheck(path: Path, ext: str) -> None:
    """Run the checks for this extension (raises FileFormatError naming the file)."""
    size = os.path.getsize(path)
    if ext in TEXT_FORMATS:
        check_text(path, ext.lstrip(".").upper())
    elif ext == ".stl":
        _check_stl(path, size)
    elif ext == ".glb":
        _check_glb(path, size)
    elif ext == ".vtk":
        _check_vtk(path)
    elif ext == ".ply":
        _check_ply(path)
    elif ext == ".vtu":
        _check_vtu(path, size)

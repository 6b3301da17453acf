"""PLY (ascii and binary) vertices via plyfile's header parser; only the vertex element is read."""

from __future__ import annotations

import io
import os
from pathlib import Path

import numpy as np
import plyfile

from core.errors import FileFormatError

NORMAL_NAMES = ("nx", "ny", "nz")
WEIGHT_NAMES = ("weight", "weights")
COLOR_NAMES = (("red", "green", "blue"), ("r", "g", "b"), ("diffuse_red", "diffuse_green",
                                                           "diffuse_blue"))


def _header(fh, path: Path) -> plyfile.PlyData:
    """The parsed header (elements, format, comments); the stream is left at the body."""
    try:
        return plyfile.PlyData._parse_header(fh)
    except (plyfile.PlyParseError, ValueError, UnicodeDecodeError) as exc:
        raise FileFormatError(f"{path}: bad PLY header ({exc})") from None


def _has_lists(element: plyfile.PlyElement) -> bool:
    """True when the element has variable-length list properties."""
    return any(isinstance(p, plyfile.PlyListProperty) for p in element.properties)


def _check_size(header: plyfile.PlyData, body: int, path: Path) -> None:
    """Refuse element counts the file is too small to hold (bogus or truncated headers)."""
    need = 0
    for el in header.elements:
        if header.text:
            row = sum(1 if isinstance(p, plyfile.PlyListProperty) else 2 for p in el.properties)
        else:
            row = el.dtype(header.byte_order).itemsize if not _has_lists(el) else 1
        need += el.count * max(row, 1)
    if need > body:
        raise FileFormatError(f"{path}: truncated PLY (header promises more data than the "
                              f"{body:,} bytes after it)")


def _vertex_table(fh, header: plyfile.PlyData, path: Path) -> np.ndarray:
    """Structured array of the vertex element, skipping whatever comes before it."""
    names = [el.name for el in header.elements]
    if "vertex" not in names:
        raise FileFormatError(f"{path}: PLY has no 'vertex' element")
    pos = names.index("vertex")
    before, vertex = header.elements[:pos], header.elements[pos]
    if _has_lists(vertex) or (not header.text and any(_has_lists(e) for e in before)):
        return _read_whole(path)["vertex"].data
    if header.text:
        return _read_ascii(fh, vertex, sum(e.count for e in before), path)
    fh.seek(sum(e.count * e.dtype(header.byte_order).itemsize for e in before), os.SEEK_CUR)
    dtype = vertex.dtype(header.byte_order)
    raw = fh.read(vertex.count * dtype.itemsize)
    if len(raw) < vertex.count * dtype.itemsize:
        raise FileFormatError(f"{path}: truncated PLY ({len(raw) // dtype.itemsize:,} of "
                              f"{vertex.count:,} vertices)")
    return np.frombuffer(raw, dtype=dtype)


def _read_ascii(fh, vertex: plyfile.PlyElement, skip: int, path: Path) -> np.ndarray:
    """ASCII vertex rows through numpy's C parser."""
    dtype = vertex.dtype()
    text = io.TextIOWrapper(fh, encoding="ascii", errors="replace")
    try:
        table = np.loadtxt(text, dtype=np.float64, skiprows=skip, max_rows=vertex.count,
                           ndmin=2, usecols=range(len(vertex.properties)))
    except ValueError as exc:
        raise FileFormatError(f"{path}: bad PLY vertex data ({exc})") from None
    finally:
        text.detach()  # the caller owns and closes the binary stream
    if len(table) < vertex.count:
        raise FileFormatError(f"{path}: truncated PLY ({len(table):,} of "
                              f"{vertex.count:,} vertices)")
    out = np.empty(len(table), dtype=dtype)
    for i, name in enumerate(dtype.names):
        out[name] = table[:, i]
    return out


def _read_whole(path: Path) -> plyfile.PlyData:
    """Fallback: let plyfile read everything (vertex elements with list properties)."""
    try:
        return plyfile.PlyData.read(str(path))
    except (plyfile.PlyParseError, ValueError) as exc:
        raise FileFormatError(f"{path}: bad PLY data ({exc})") from None


def _attributes(table: np.ndarray) -> dict[str, np.ndarray]:
    """Normals, colours and every other scalar vertex property."""
    names = set(table.dtype.names)
    attrs: dict[str, np.ndarray] = {}
    used = {"x", "y", "z"}
    if names.issuperset(NORMAL_NAMES):
        attrs["normals"] = np.column_stack([table[n] for n in NORMAL_NAMES]).astype(np.float64)
        used.update(NORMAL_NAMES)
    for triple in COLOR_NAMES:
        if names.issuperset(triple):
            attrs["colors"] = np.column_stack([table[n] for n in triple]).astype(np.uint8)
            used.update(triple)
            break
    for name in table.dtype.names:
        if name not in used and table.dtype[name].shape == ():
            key = "weights" if name in WEIGHT_NAMES else name
            attrs[key] = np.asarray(table[name], dtype=np.float64)
    return attrs


def read_ply(path: Path, columns=None) -> tuple[np.ndarray, dict[str, np.ndarray], tuple]:
    """(n, 3) or (n, 2) vertex coordinates, vertex attributes, and header comments as notes."""
    with open(path, "rb") as fh:
        header = _header(fh, path)
        _check_size(header, os.fstat(fh.fileno()).st_size - fh.tell(), path)
        table = _vertex_table(fh, header, path)
    names = table.dtype.names or ()
    axes = [a for a in ("x", "y", "z") if a in names]
    if axes[:2] != ["x", "y"]:
        raise FileFormatError(f"{path}: PLY vertices have no x/y properties ({', '.join(names)})")
    points = np.column_stack([table[a] for a in axes]).astype(np.float64)
    notes = tuple(f"comment {c}" for c in header.comments[:5])
    return points, _attributes(table), notes

"""PLY (ascii and binary) vertices: our own header parser; only the vertex element is read,
its scalar properties as coordinates and attributes (list properties are skipped)."""

from __future__ import annotations

import io
import os
from pathlib import Path

import numpy as np

from core.errors import FileFormatError
from core.io.ply_body import read_ascii_rows, read_binary
from core.io.ply_faces import face_note
from core.io.ply_header import Element, Header, parse_header

NORMAL_NAMES = ("nx", "ny", "nz")
WEIGHT_NAMES = ("weight", "weights")
COLOR_NAMES = (("red", "green", "blue"), ("r", "g", "b"), ("diffuse_red", "diffuse_green",
                                                           "diffuse_blue"))


def check_size(header: Header, body: int, path: Path) -> None:
    """Refuse element counts the file is too small to hold (bogus or truncated headers)."""
    need = 0
    for el in header.elements:
        if header.text:
            row = sum(1 if p.count is not None else 2 for p in el.properties)
        else:
            row = sum((p.count or p.dtype).itemsize for p in el.properties)  # lists may be empty
        need += el.n * max(row, 1)
    if need > body:
        raise FileFormatError(f"{path}: truncated PLY (header promises more data than the "
                              f"{body:,} bytes after it)")


def _vertex_table(fh, header: Header, path: Path) -> np.ndarray:
    """Structured array of the vertex element's scalar properties (lists skipped)."""
    names = [el.name for el in header.elements]
    if "vertex" not in names:
        raise FileFormatError(f"{path}: PLY has no 'vertex' element")
    pos = names.index("vertex")
    before, vertex = header.elements[:pos], header.elements[pos]
    if header.text:
        return _read_ascii(fh, vertex, sum(e.n for e in before), path)
    if not any(e.has_lists for e in before):  # seek past fixed-size rows, read only the vertices
        fh.seek(sum(e.n * e.row_dtype().itemsize for e in before), os.SEEK_CUR)
        size = -1 if vertex.has_lists else vertex.n * vertex.row_dtype().itemsize
        return read_binary(memoryview(fh.read(size)), 0, vertex, str(path))[0]
    buf, at = memoryview(fh.read()), 0
    for element in before:
        _, at = read_binary(buf, at, element, str(path))
    return read_binary(buf, at, vertex, str(path))[0]


def _read_ascii(fh, vertex: Element, skip: int, path: Path) -> np.ndarray:
    """ASCII vertex rows: numpy's C parser, or row by row when the vertex has lists."""
    for _ in range(skip):
        if not fh.readline():
            break
    if vertex.has_lists:
        lines = [fh.readline() for _ in range(vertex.n)]
        lines = [ln for ln in lines if ln.strip()]
        table = read_ascii_rows(lines, vertex, str(path))
    else:
        text = io.TextIOWrapper(fh, encoding="ascii", errors="replace")
        try:
            values = np.loadtxt(text, dtype=np.float64, max_rows=vertex.n, ndmin=2,
                                usecols=range(len(vertex.properties)))
        except ValueError:
            raise FileFormatError(f"{path}: bad PLY vertex data (a value is not a number or "
                                  "a row is short)") from None
        finally:
            text.detach()  # the caller owns and closes the binary stream
        table = np.empty(len(values), dtype=vertex.row_dtype())
        for i, name in enumerate(table.dtype.names):
            table[name] = values[:, i]
    if len(table) < vertex.n:
        raise FileFormatError(f"{path}: truncated PLY ({len(table):,} of "
                              f"{vertex.n:,} vertices)")
    return table


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
        header = parse_header(fh, str(path))
        body_start = fh.tell()
        check_size(header, os.fstat(fh.fileno()).st_size - body_start, path)
        table = _vertex_table(fh, header, path)
        faces = face_note(fh, body_start, header, len(table), str(path))
    names = table.dtype.names or ()
    axes = [a for a in ("x", "y", "z") if a in names]
    if axes[:2] != ["x", "y"]:
        raise FileFormatError(f"{path}: PLY vertices have no x/y properties ({', '.join(names)})")
    points = np.column_stack([table[a] for a in axes]).astype(np.float64)
    notes = (*faces, *header.notes, *(f"comment {c}" for c in header.comments[:5]))
    return points, _attributes(table), notes

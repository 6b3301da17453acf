"""Text and PLY point files read in chunks (for tiled runs), parsed exactly as core.io
parses them whole, so a file bigger than memory never has all its points in one array.

Only what a whole read would return unchanged is streamed: plain coordinates (no weight or
radius column, no longitude/latitude to project, a PLY vertex without list properties).
Anything else, and files small enough to read whole (STREAM_FROM_BYTES), go through core.io.
"""

from __future__ import annotations

import io
import itertools
import os
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from core.build.points import first_too_large, too_large_message
from core.errors import FileFormatError
from core.io.geographic import geographic_axes
from core.io.ply import WEIGHT_NAMES, check_size
from core.io.ply_header import Element, parse_header
from core.io.precheck import precheck
from core.io.text import choose_columns, sniff
from core.io.text_rows import Layout, row_chunks

#: Files from this size on are streamed; smaller ones are read whole (their planar or
#: geographic points are then handled as the window handles them).
STREAM_FROM_BYTES = 64 << 20
#: Rows per chunk.
CHUNK_ROWS = 1 << 20
TEXT_SUFFIXES = (".xyz", ".txt", ".csv", ".pts")


@contextmanager
def _readable(path: Path) -> Iterator[None]:
    """An OS error while streaming `path` (a file removed or cut meanwhile) in words."""
    try:
        yield
    except OSError as exc:
        raise FileFormatError(f"{path}: cannot be read ({(exc.strerror or str(exc)).lower()})"
                              ) from exc


def _finite(xyz: np.ndarray, path: Path, first: int) -> np.ndarray:
    """Rows with finite coordinates only (core.io drops the others too); a coordinate too
    large for an alpha shape is core.io's error, naming its point (rows from `first`)."""
    extreme = first_too_large(xyz)
    if extreme is not None:
        row, value = extreme
        raise FileFormatError(f"{path}: {too_large_message(xyz, first + row, value)}")
    return xyz[np.isfinite(xyz).all(axis=1)]


class _Unprojected:
    """A streamed file's points are never projected: their dimension is the file's."""

    dim: int

    @property
    def ambient_dim(self) -> int:
        """Dimension of the file's points (the same as `dim`)."""
        return self.dim


@dataclass(frozen=True)
class TextSource(_Unprojected):
    """A delimited text file (XYZ, TXT, CSV, PTS) read `chunk` lines at a time."""

    path: Path
    layout: Layout
    usecols: tuple[int, ...]
    chunk: int = CHUNK_ROWS
    weights: None = None
    frame: None = None

    @classmethod
    def open(cls, path: Path, chunk: int = CHUNK_ROWS) -> TextSource | None:
        """The source, or None when a whole read would change the columns (weights or
        radii, longitude/latitude)."""
        layout = sniff(path)
        coords, attributes = choose_columns(layout, None, path)
        if "weights" in attributes or "radius" in attributes:
            return None
        if layout.names and geographic_axes([layout.names[c] for c in coords]) is not None:
            return None
        return cls(path, layout, tuple(coords), chunk)

    @property
    def dim(self) -> int:
        """Dimension of the points (2 or 3 coordinate columns)."""
        return len(self.usecols)

    def chunks(self) -> Iterator[tuple[np.ndarray, None]]:
        """(coords, None) chunks in file order."""
        with _readable(self.path):
            first = 0
            for table in row_chunks(self.path, self.layout, list(self.usecols), self.chunk):
                yield _finite(table, self.path, first), None
                first += len(table)


@dataclass(frozen=True)
class PlySource(_Unprojected):
    """A PLY file's vertices (ASCII or binary, without list properties) read in chunks."""

    path: Path
    axes: tuple[str, ...]
    chunk: int = CHUNK_ROWS
    weights: None = None
    frame: None = None

    @classmethod
    def open(cls, path: Path, chunk: int = CHUNK_ROWS) -> PlySource | None:
        """The source, or None when the vertex element cannot be streamed (list properties,
        list elements before it in a binary file, a weight or radius property)."""
        before, vertex = _vertex_element(path)
        names = [p.name for p in vertex.properties]
        if vertex.has_lists or any(n in (*WEIGHT_NAMES, "radius") for n in names):
            return None
        if any(e.has_lists for e in before):
            return None
        return cls(path, tuple(a for a in ("x", "y", "z") if a in names), chunk)

    @property
    def dim(self) -> int:
        """Dimension of the points (x, y and z if the vertices have it)."""
        return len(self.axes)

    def chunks(self) -> Iterator[tuple[np.ndarray, None]]:
        """(coords, None) chunks in file order, each value through its property's type (as
        core.io.ply reads it)."""
        with _readable(self.path), open(self.path, "rb") as fh:
            header = parse_header(fh, str(self.path))
            names = [e.name for e in header.elements]
            if "vertex" not in names:  # the file was rewritten since the source was opened
                raise FileFormatError(f"{self.path}: PLY has no 'vertex' element")
            at = names.index("vertex")
            vertex, before = header.elements[at], header.elements[:at]
            tables = (_text_rows(fh, vertex, sum(e.n for e in before), self.chunk)
                      if header.text else _binary_rows(fh, vertex, before, self.chunk))
            read = 0
            for table in tables:
                xyz = np.column_stack([table[a] for a in self.axes]).astype(np.float64)
                yield _finite(xyz, self.path, read), None
                read += len(table)
        if read < vertex.n:
            raise FileFormatError(f"{self.path}: truncated PLY ({read:,} of {vertex.n:,} "
                                  "vertices)")


def _vertex_element(path: Path) -> tuple[list[Element], Element]:
    """(elements before the vertex element, the vertex element); the same checks of the
    header and the file's size as core.io.ply."""
    with open(path, "rb") as fh:
        header = parse_header(fh, str(path))
        check_size(header, os.fstat(fh.fileno()).st_size - fh.tell(), path)
    names = [e.name for e in header.elements]
    if "vertex" not in names:
        raise FileFormatError(f"{path}: PLY has no 'vertex' element")
    vertex = header.elements[names.index("vertex")]
    properties = [p.name for p in vertex.properties if p.count is None]  # lists: skipped
    if [a for a in ("x", "y", "z") if a in properties][:2] != ["x", "y"]:
        raise FileFormatError(f"{path}: PLY vertices have no x/y properties "
                              f"({', '.join(properties)})")
    return header.elements[: names.index("vertex")], vertex


def _binary_rows(fh, vertex: Element, before: list[Element], chunk: int
                 ) -> Iterator[np.ndarray]:
    """Structured rows of a binary vertex element, `chunk` at a time (a short read ends)."""
    fh.seek(sum(e.n * e.row_dtype().itemsize for e in before), os.SEEK_CUR)
    dtype = vertex.row_dtype()
    for lo in range(0, vertex.n, chunk):
        want = min(chunk, vertex.n - lo)
        data = fh.read(want * dtype.itemsize)
        rows = np.frombuffer(data, dtype=dtype, count=len(data) // dtype.itemsize)
        if len(rows):
            yield rows
        if len(rows) < want:
            return


def _text_rows(fh, vertex: Element, skip: int, chunk: int) -> Iterator[np.ndarray]:
    """Rows of an ASCII vertex element, `chunk` lines at a time, cast to the properties'
    types (a short file ends early)."""
    text = io.TextIOWrapper(fh, encoding="ascii", errors="replace")
    try:
        lines = itertools.islice(_data_lines(itertools.islice(text, skip, None)), vertex.n)
        while batch := list(itertools.islice(lines, chunk)):
            try:
                values = np.loadtxt(batch, dtype=np.float64, ndmin=2,
                                    usecols=range(len(vertex.properties)))
            except ValueError:
                raise FileFormatError(f"{fh.name}: bad PLY vertex data (a value is not a "
                                      "number or a row is short)") from None
            table = np.empty(len(values), dtype=vertex.row_dtype())
            for i, name in enumerate(table.dtype.names):
                table[name] = values[:, i]
            yield table
    finally:
        text.detach()


def _data_lines(lines: Iterator[str]) -> Iterator[str]:
    """The lines holding values: np.loadtxt, reading a whole vertex element, passes over
    blank and '#' comment lines without counting them as rows."""
    return (line for line in lines if line.split("#", 1)[0].strip())


def streamed_source(path: Path, stream_from: int | None = None, chunk: int = CHUNK_ROWS
                    ) -> TextSource | PlySource | None:
    """A chunked source for a text or PLY file of at least `stream_from` bytes (default
    STREAM_FROM_BYTES) whose whole read would give its plain coordinates, else None (read it
    whole with core.io)."""
    suffix = path.suffix.lower()
    if suffix not in (*TEXT_SUFFIXES, ".ply"):
        return None
    with _readable(path):
        if not path.is_file() or path.stat().st_size < (
                STREAM_FROM_BYTES if stream_from is None else stream_from):
            return None
        precheck(path, suffix)  # NUL bytes: a damaged or sparse file, one endless line
        if suffix == ".ply":
            return PlySource.open(path, chunk)
        return TextSource.open(path, chunk)

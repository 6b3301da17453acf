"""Legacy VTK (.vtk, ascii or binary): the POINTS section is the point set.

meshio reads no POLYDATA and refuses unstructured grids with cells it does not know (poly
vertices, triangle strips...), and core must not import VTK, so the points of the datasets
that list them (POLYDATA, UNSTRUCTURED_GRID, STRUCTURED_GRID) can be read here: header,
optional FIELD block, then `POINTS n type`.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from core.errors import FileFormatError

VTK_DTYPES = {
    "float": "f4", "double": "f8", "int": "i4", "unsigned_int": "u4", "short": "i2",
    "unsigned_short": "u2", "char": "i1", "unsigned_char": "u1", "long": "i8",
    "unsigned_long": "u8", "vtktypeint64": "i8", "vtktypeuint64": "u8",
}
MAX_HEADER_LINES = 4


class _Cursor:
    """A read position in the file's bytes: whole lines, or raw values of the file's encoding."""

    def __init__(self, data: bytes, binary: bool, path: Path) -> None:
        self.data, self.pos, self.binary, self.path = data, 0, binary, path

    def line(self) -> str:
        """The next non-blank line, decoded as ASCII (empty string at the end of the file)."""
        while self.pos < len(self.data):
            end = self.data.find(b"\n", self.pos)
            end = len(self.data) if end < 0 else end
            text = self.data[self.pos : end].decode("ascii", "replace").strip()
            self.pos = end + 1
            if text:
                return text
        return ""

    def values(self, count: int, vtk_type: str) -> np.ndarray:
        """`count` numbers of a VTK type name, as float64."""
        code = VTK_DTYPES.get(vtk_type.lower())
        if code is None:
            raise FileFormatError(f"{self.path}: unknown VTK data type {vtk_type!r}")
        if self.binary:
            dtype = np.dtype(">" + code)
            end = self.pos + count * dtype.itemsize
            if end > len(self.data):
                raise FileFormatError(f"{self.path}: truncated VTK file")
            out = np.frombuffer(self.data, dtype=dtype, count=count, offset=self.pos)
            self.pos = end
            return out.astype(np.float64)
        tokens = self.data[self.pos :].split(None, count)
        if len(tokens) < count:
            raise FileFormatError(f"{self.path}: truncated VTK file")
        try:  # values rounded to the declared type, as VTK stores them
            out = np.array(tokens[:count], dtype=np.bytes_).astype(code).astype(np.float64)
        except ValueError:
            raise FileFormatError(f"{self.path}: a VTK value is not a number") from None
        self.pos = len(self.data) - (len(tokens[count]) if len(tokens) > count else 0)
        return out


def dataset_kind(path: Path) -> str:
    """The DATASET word of a legacy VTK file ('POLYDATA', 'UNSTRUCTURED_GRID'...), or ''."""
    with open(path, "rb") as fh:
        cursor = _Cursor(fh.read(4096), False, path)
    for _ in range(MAX_HEADER_LINES + 1):
        words = cursor.line().split()
        if words[:1] == ["DATASET"] and len(words) > 1:
            return words[1].upper()
    return ""


def _skip_field(cursor: _Cursor, words: list[str]) -> None:
    """Step over a `FIELD name k` block: k arrays of `name comps tuples type` + values."""
    for _ in range(int(words[2])):
        _, comps, tuples, vtk_type = cursor.line().split()[:4]
        cursor.values(int(comps) * int(tuples), vtk_type)


POINT_DATASETS = ("POLYDATA", "UNSTRUCTURED_GRID", "STRUCTURED_GRID")


def read_points_section(path: Path) -> np.ndarray:
    """(n, 3) float64 points of a legacy VTK dataset with a POINTS section."""
    data = path.read_bytes()
    head = _Cursor(data, False, path)
    if not head.line().startswith("# vtk DataFile"):
        raise FileFormatError(f"{path}: not a legacy VTK file: the first line must be "
                              "'# vtk DataFile Version ...'")
    head.line()  # title
    encoding = head.line().upper()
    if encoding not in ("ASCII", "BINARY"):
        raise FileFormatError(f"{path}: VTK file is neither ASCII nor BINARY ({encoding[:20]!r})")
    cursor = _Cursor(data, encoding == "BINARY", path)
    cursor.pos = head.pos
    try:
        while words := cursor.line().split():
            if words[0].upper() == "FIELD":
                _skip_field(cursor, words)
            elif words[0].upper() == "POINTS":
                n = int(words[1])
                if n < 0:
                    raise ValueError(n)
                return cursor.values(3 * n, words[2]).reshape(n, 3)
    except (ValueError, IndexError):
        raise FileFormatError(f"{path}: bad VTK header line") from None
    raise FileFormatError(f"{path}: VTK dataset without a POINTS section")

"""Which PLY vertices the faces use, for the load report only (every vertex is a point either
way): the `face` element's vertex_indices list, read in a second pass over the file."""

from __future__ import annotations

import itertools

import numpy as np

from core.errors import FileFormatError
from core.io.obj import vertex_note
from core.io.ply_body import element_rows, read_binary
from core.io.ply_header import Element, Header

FACE_LISTS = ("vertex_indices", "vertex_index")


def _face(header: Header) -> tuple[int, str] | None:
    """(element index, list property name) of the faces, or None when there are none."""
    for i, element in enumerate(header.elements):
        names = [p.name for p in element.properties if p.count is not None]
        found = next((n for n in FACE_LISTS if n in names), None)
        if element.name == "face" and found:
            return i, found
    return None


def _ascii_items(fh, header: Header, index: int, name: str, where: str) -> np.ndarray:
    """Indices of one list property of an ascii element (one text line per row): numpy's C
    parser when every row is the same polygon size, else row by row."""
    element = header.elements[index]
    for _ in range(sum(e.n for e in header.elements[:index])):
        fh.readline()
    at = [p.name for p in element.properties].index(name)
    if at == 0 and element.n:
        start = fh.tell()
        try:
            table = np.loadtxt(itertools.islice(fh, element.n), dtype=np.int64, ndmin=2)
            if len(table) == element.n and np.all(table[:, 0] == table.shape[1] - 1):
                return table[:, 1:].ravel()
        except ValueError:  # rows of different lengths (mixed polygons)
            pass
        fh.seek(start)
    rows = [ln.split() for ln in itertools.islice(fh, element.n)]
    if len(rows) < element.n:
        raise FileFormatError(f"{where}: truncated PLY (faces)")
    parts = [_row_items(r, element, at, where) for r in rows]
    return np.concatenate(parts) if parts else np.zeros(0, dtype=np.int64)


def _row_items(tokens: list[bytes], element: Element, at: int, where: str) -> np.ndarray:
    """The items of list property number `at` in one ascii row."""
    pos = 0
    for i, p in enumerate(element.properties):
        if p.count is None:
            pos += 1
            continue
        n = int(tokens[pos])
        if i == at:
            return np.array(tokens[pos + 1 : pos + 1 + n], dtype=np.bytes_).astype(np.int64)
        pos += 1 + n
    raise FileFormatError(f"{where}: bad PLY face row")


def face_note(fh, body_start: int, header: Header, n_vertices: int, where: str) -> tuple:
    """('mesh vertices: ... used by no face',) or () when the file has no faces; a face element
    that cannot be read only gives a note saying so (it never stops the points)."""
    found = _face(header)
    if found is None:
        return ()
    index, name = found
    fh.seek(body_start)
    try:
        if header.text:
            items = _ascii_items(fh, header, index, name, where)
        else:
            buf, pos = memoryview(fh.read()), 0
            for element in header.elements[:index]:
                pos = read_binary(buf, pos, element, where)[1]
            items = element_rows(buf, pos, header.elements[index], name, where)
    except (FileFormatError, ValueError, IndexError):
        return ("PLY faces could not be read; which vertices they use is not known",)
    items = items[(items >= 0) & (items < n_vertices)]
    used = int(np.count_nonzero(np.bincount(items, minlength=n_vertices)))
    return (vertex_note(n_vertices, used, header.elements[index].n),)

"""PLY element data: the scalar properties of one element, list properties skipped.

Rows whose lists all have the length of the first row's lists (the usual case: triangles,
one index per range-grid cell) are read as one strided array; other rows are walked one by one.
"""

from __future__ import annotations

import numpy as np

from core.errors import FileFormatError
from core.io.ply_header import Element


def _fixed_dtype(element: Element, counts: list[int]) -> np.dtype:
    """Row dtype when every list of the element has the given lengths."""
    fields, lists = [], iter(counts)
    for i, p in enumerate(element.properties):
        if p.count is None:
            fields.append((p.name, p.dtype))
        else:
            fields.append((f"__count{i}", p.count))
            fields.append((f"__items{i}", p.dtype, (next(lists),)))
    return np.dtype(fields)


def _first_counts(buf: memoryview, pos: int, element: Element, where: str) -> list[int]:
    """List lengths in the element's first row."""
    counts = []
    for p in element.properties:
        if pos + (p.count or p.dtype).itemsize > len(buf):
            raise FileFormatError(f"{where}: truncated PLY ({element.name} data)")
        if p.count is None:
            pos += p.dtype.itemsize
        else:
            n = int(np.frombuffer(buf, p.count, 1, pos)[0])
            if n < 0:
                raise FileFormatError(f"{where}: bad PLY: negative list length")
            counts.append(n)
            pos += p.count.itemsize + n * p.dtype.itemsize
    return counts


def _walk(buf: memoryview, pos: int, element: Element, where: str) -> tuple[dict, int]:
    """Byte offset of every scalar property in every row (rows with lists of any length)."""
    offsets = {p.name: np.empty(element.n, dtype=np.int64)
               for p in element.properties if p.count is None}
    for row in range(element.n):
        for p in element.properties:
            if p.count is None:
                offsets[p.name][row] = pos
                pos += p.dtype.itemsize
            else:
                if pos + p.count.itemsize > len(buf):
                    raise FileFormatError(f"{where}: truncated PLY ({element.name} data)")
                n = int(np.frombuffer(buf, p.count, 1, pos)[0])
                if n < 0:
                    raise FileFormatError(f"{where}: bad PLY: negative list length")
                pos += p.count.itemsize + n * p.dtype.itemsize
    if pos > len(buf):
        raise FileFormatError(f"{where}: truncated PLY ({element.name} data)")
    return offsets, pos


def _gather(buf: memoryview, offsets: dict, element: Element) -> np.ndarray:
    """Structured array of the scalar properties, picked at their byte offsets."""
    data = np.frombuffer(buf, dtype=np.uint8)
    scalars = [p for p in element.properties if p.count is None]
    out = np.empty(element.n, dtype=[(p.name, p.dtype) for p in scalars])
    for p in scalars:
        idx = offsets[p.name][:, None] + np.arange(p.dtype.itemsize)
        out[p.name] = data[idx].reshape(-1).view(p.dtype)
    return out


def read_binary(buf: memoryview, pos: int, element: Element, where: str) -> tuple:
    """(structured array of the scalar properties, position after the element)."""
    if element.n == 0:
        return np.empty(0, dtype=[(p.name, p.dtype) for p in element.properties
                                  if p.count is None]), pos
    counts = _first_counts(buf, pos, element, where) if element.has_lists else []
    dtype = _fixed_dtype(element, counts)
    end = pos + element.n * dtype.itemsize
    if not element.has_lists and end > len(buf):
        have = max(len(buf) - pos, 0) // dtype.itemsize
        raise FileFormatError(f"{where}: truncated PLY ({have:,} of {element.n:,} "
                              f"{element.name} rows)")
    if end <= len(buf):
        rows = np.frombuffer(buf, dtype=dtype, count=element.n, offset=pos)
        count_names = [n for n in dtype.names if n.startswith("__count")]
        if all(np.all(rows[c] == k) for c, k in zip(count_names, counts, strict=True)):
            return _scalars(rows, element), end
    offsets, end = _walk(buf, pos, element, where)
    return _gather(buf, offsets, element), end


def _scalars(rows: np.ndarray, element: Element) -> np.ndarray:
    """Copy of the scalar fields only."""
    names = [p.name for p in element.properties if p.count is None]
    out = np.empty(len(rows), dtype=[(n, rows.dtype[n]) for n in names])
    for n in names:
        out[n] = rows[n]
    return out


def read_ascii_rows(lines: list[bytes], element: Element, where: str) -> np.ndarray:
    """Structured array of the scalar properties from one text line per row."""
    scalars = [p for p in element.properties if p.count is None]
    out = np.empty(len(lines), dtype=[(p.name, p.dtype) for p in scalars])
    table = np.empty((len(lines), len(scalars)), dtype=np.float64)
    for row, line in enumerate(lines):
        table[row] = _ascii_scalars(line.split(), element, where)
    for i, p in enumerate(scalars):
        out[p.name] = table[:, i]
    return out


def _ascii_scalars(tokens: list[bytes], element: Element, where: str) -> list[float]:
    """Scalar values of one ascii row, stepping over its lists."""
    vals, pos = [], 0
    try:
        for p in element.properties:
            if p.count is None:
                vals.append(float(tokens[pos]))
                pos += 1
            else:
                pos += 1 + int(tokens[pos])
    except (IndexError, ValueError):
        raise FileFormatError(f"{where}: bad PLY {element.name} row {b' '.join(tokens)[:60]!r}"
                              ) from None
    return vals


def element_rows(buf: memoryview, pos: int, element: Element, name: str, where: str
                 ) -> np.ndarray:
    """(k,) int64: every item of list property `name` of a binary element, row after row."""
    counts = _first_counts(buf, pos, element, where)
    dtype = _fixed_dtype(element, counts)
    at = [p.name for p in element.properties].index(name)
    end = pos + element.n * dtype.itemsize
    if end <= len(buf):
        rows = np.frombuffer(buf, dtype=dtype, count=element.n, offset=pos)
        count_names = [n for n in dtype.names if n.startswith("__count")]
        if all(np.all(rows[c] == k) for c, k in zip(count_names, counts, strict=True)):
            return rows[f"__items{at}"].astype(np.int64).ravel()
    return _walk_items(buf, pos, element, at, where)


def _walk_items(buf: memoryview, pos: int, element: Element, at: int, where: str
                ) -> np.ndarray:
    """element_rows for rows whose lists differ in length (mixed polygons), row by row."""
    out = []
    for _ in range(element.n):
        for i, p in enumerate(element.properties):
            if p.count is None:
                pos += p.dtype.itemsize
                continue
            if pos + p.count.itemsize > len(buf):
                raise FileFormatError(f"{where}: truncated PLY ({element.name} data)")
            n = int(np.frombuffer(buf, p.count, 1, pos)[0])
            pos += p.count.itemsize
            if n < 0 or pos + n * p.dtype.itemsize > len(buf):
                raise FileFormatError(f"{where}: truncated PLY ({element.name} data)")
            if i == at:
                out.append(np.frombuffer(buf, p.dtype, n, pos).astype(np.int64))
            pos += n * p.dtype.itemsize
    return np.concatenate(out) if out else np.zeros(0, dtype=np.int64)

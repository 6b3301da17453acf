"""Fast delimited text: rows formatted a chunk at a time by one %-format, no per-row Python."""

from __future__ import annotations

from collections.abc import Sequence
from typing import TextIO

import numpy as np

CHUNK_ROWS = 1 << 16  # rows formatted per string; bounds the memory of one write


def format_rows(fmt: str, columns: Sequence[np.ndarray]) -> str:
    """The rows of equal-length `columns`, each formatted by `fmt` (one %-field per column).

    `fmt` usually ends in a newline. Values go through .tolist(), so %d gets Python ints,
    %r and %.17g Python floats (repr / round-trip text) and %s Python strings.
    """
    n, m = len(columns[0]), len(columns)
    values: list = [None] * (n * m)
    for j, col in enumerate(columns):
        values[j::m] = np.asarray(col).tolist()
    return (fmt * n) % tuple(values)


def write_rows(fh: TextIO, fmt: str, columns: Sequence[np.ndarray],
               chunk: int | None = None) -> None:
    """Write format_rows(fmt, columns) to `fh`, `chunk` (default CHUNK_ROWS) rows at a time."""
    chunk = chunk or CHUNK_ROWS
    for start in range(0, len(columns[0]), chunk):
        fh.write(format_rows(fmt, [col[start:start + chunk] for col in columns]))

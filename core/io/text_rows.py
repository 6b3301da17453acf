"""Rows of a delimited text point file once its layout is known: numpy's C parser first, a
careful line-by-line pass (missing values, the line of a bad value) when that fails. Lines are
rewritten to plain float syntax (core.io.numbers) and a PTS file's scan count lines set aside."""

from __future__ import annotations

import csv
import itertools
import re
import warnings
from collections.abc import Iterable, Iterator
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from core.errors import FileFormatError
from core.io.numbers import NumberStyle

MISSING = {"", "na", "nan", "null", "none", "n/a"}
COMMENTS = ("#", "//", "%")
PTS_COUNT = re.compile(r"^\s*\d+\s*$")  # a PTS scan's point count line


@dataclass(frozen=True)
class Layout:
    """How a text table is laid out: delimiter (None = whitespace), header names, rows to skip."""

    delimiter: str | None
    names: list[str] | None
    skiprows: int
    n_cols: int
    first_row: list[str]
    style: NumberStyle = field(default_factory=NumberStyle)
    pts: bool = False


def split(line: str, delimiter: str | None) -> list[str]:
    """Split one line like the csv module (quotes respected) or on runs of whitespace."""
    if delimiter is None:
        return line.split()
    return next(csv.reader([line], delimiter=delimiter, skipinitialspace=True), [])


def is_number(token: str) -> bool:
    """True when `token` parses as a float."""
    try:
        float(token)
    except ValueError:
        return False
    return True


def uncomment(line: str) -> str:
    """The line without a trailing '# comment'."""
    return line.split("#", 1)[0] if "#" in line else line


def _lines(fh: Iterable[str], layout: Layout, counts: list[int]) -> Iterator[str]:
    """Lines from the first data row on, in plain float syntax; a PTS file's count lines are
    appended to `counts` and replaced by blank lines (so line numbers stay right)."""
    lines: Iterator[str] = iter(fh) if layout.pts else itertools.islice(fh, layout.skiprows, None)
    if layout.pts:
        lines = _without_counts(lines, counts)
    return lines if layout.style.plain else map(layout.style.fix(), lines)


def _without_counts(lines: Iterator[str], counts: list[int]) -> Iterator[str]:
    """PTS: each scan starts with a line holding only its point count."""
    for line in lines:
        if PTS_COUNT.match(line):
            counts.append(int(line))
            yield "\n"
        else:
            yield line


def _fast_options(layout: Layout, usecols: list[int]) -> dict:
    """np.loadtxt's options for this layout (numpy allows quotes with one comment marker only)."""
    quoted = layout.delimiter is not None
    return {"delimiter": layout.delimiter, "quotechar": '"' if quoted else None,
            "usecols": usecols, "comments": "#" if quoted else COMMENTS, "ndmin": 2,
            "dtype": np.float64}


def _read_fast(path: Path, layout: Layout, usecols: list[int]) -> tuple[np.ndarray, list[int]]:
    """numpy's C parser; raises ValueError on anything unusual (missing values, ragged rows)."""
    options = _fast_options(layout, usecols)
    counts: list[int] = []
    if layout.style.plain and not layout.pts:
        return np.loadtxt(path, skiprows=layout.skiprows, encoding="utf-8-sig", **options), counts
    with open(path, encoding="utf-8-sig") as fh:
        return np.loadtxt(_lines(fh, layout, counts), **options), counts


def _first_line(layout: Layout) -> int:
    """The line number (from 1) of the first line _lines yields."""
    return 1 if layout.pts else layout.skiprows + 1


def _parse_lines(lines: Iterable[str], layout: Layout, usecols: list[int], path: Path,
                 first: int) -> np.ndarray:
    """Line by line: missing values become NaN; a bad value is reported with its line."""
    out = []
    for lineno, line in enumerate(lines, first):
        if not line.strip() or line.lstrip().startswith(COMMENTS):
            continue
        row = split(uncomment(line), layout.delimiter)
        out.append(_parse_row(row, usecols, path, lineno))
    return np.array(out, dtype=np.float64).reshape(-1, len(usecols))


def _read_careful(path: Path, layout: Layout, usecols: list[int]) -> tuple[np.ndarray, list[int]]:
    """The whole file parsed line by line (_parse_lines)."""
    counts: list[int] = []
    with open(path, encoding="utf-8-sig", errors="replace") as fh:
        table = _parse_lines(_lines(fh, layout, counts), layout, usecols, path,
                             _first_line(layout))
    return table, counts


def row_chunks(path: Path, layout: Layout, usecols: list[int], lines: int
               ) -> Iterator[np.ndarray]:
    """read_rows's table in pieces of at most `lines` lines, parsed alike (numpy's parser,
    the careful pass for a piece it refuses), so a file bigger than memory can be streamed."""
    options = _fast_options(layout, usecols)
    first = _first_line(layout)
    with open(path, encoding="utf-8-sig", errors="replace") as fh:
        source = _lines(fh, layout, [])
        while batch := list(itertools.islice(source, lines)):
            try:
                with warnings.catch_warnings():  # a piece of comments only holds no data
                    warnings.filterwarnings("ignore", "loadtxt: input contained no data")
                    table = np.loadtxt(batch, **options)
            except ValueError:
                table = _parse_lines(batch, layout, usecols, path, first)
            first += len(batch)
            if len(table):
                yield table


def pts_note(counts: list[int], n_rows: int) -> tuple[str, ...]:
    """Report line for a PTS file: its scans, and any count that disagrees with the rows."""
    if not counts:
        return ()
    note = f"PTS: {len(counts)} scan{'s' if len(counts) > 1 else ''}, {n_rows:,} points read"
    if sum(counts) != n_rows:
        note += f" (the count lines promise {sum(counts):,})"
    return (note,)


def _parse_row(row: list[str], usecols: list[int], path: Path, lineno: int) -> list[float]:
    """Floats of the chosen cells of one row; missing cells are NaN."""
    if len(row) <= max(usecols):
        raise FileFormatError(f"{path}: line {lineno} has {len(row)} columns, "
                              f"column {max(usecols) + 1} needed")
    vals = []
    for c in usecols:
        cell = row[c].strip()
        if cell.lower() in MISSING:
            vals.append(np.nan)
        elif is_number(cell):
            vals.append(float(cell))
        else:
            raise FileFormatError(f"{path}: non-numeric value {cell[:40]!r} at line {lineno}, "
                                  f"column {c + 1}")
    return vals


def read_rows(path: Path, layout: Layout, usecols: list[int]) -> tuple[np.ndarray, list[int]]:
    """((n, len(usecols)) float64 table, PTS scan counts) of the file's data rows."""
    try:
        return _read_fast(path, layout, usecols)
    except ValueError:
        return _read_careful(path, layout, usecols)

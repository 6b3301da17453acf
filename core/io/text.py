"""Delimited text point files (XYZ, PTS, TXT, CSV): delimiter, header and column sniffing."""

from __future__ import annotations

import csv
import itertools
import re
from collections.abc import Iterable, Iterator
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from core.errors import FileFormatError
from core.io.columns import clean_name, explicit_columns, named_attributes, named_coordinates
from core.io.numbers import NumberStyle, number_style

SNIFF_BYTES = 1 << 16
DELIMITERS = (",", ";", "\t", "|")
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


def _split(line: str, delimiter: str | None) -> list[str]:
    """Split one line like the csv module (quotes respected) or on runs of whitespace."""
    if delimiter is None:
        return line.split()
    return next(csv.reader([line], delimiter=delimiter, skipinitialspace=True), [])


def _is_number(token: str) -> bool:
    """True when `token` parses as a float."""
    try:
        float(token)
    except ValueError:
        return False
    return True


def _head_lines(path: Path) -> list[str]:
    """The first lines of the file as text; binary or undecodable content is a format error."""
    with open(path, "rb") as fh:
        head = fh.read(SNIFF_BYTES)
    if b"\0" in head:
        raise FileFormatError(f"{path}: binary content in a text point file")
    head = head.removeprefix(b"\xef\xbb\xbf")  # a UTF-8 byte order mark is no data
    try:
        text = head.decode("utf-8")
    except UnicodeDecodeError as exc:
        if exc.start < len(head) - 4:  # a cut multi-byte character at the end is fine
            text = head.decode("latin-1")
        else:
            text = head[: exc.start].decode("utf-8")
    lines = text.splitlines()
    return lines[:-1] if len(head) == SNIFF_BYTES and len(lines) > 1 else lines


def _delimiter(lines: list[str]) -> str | None:
    """The delimiter present with the same count on every sampled line, else whitespace."""
    sample = lines[:20]
    for d in DELIMITERS:
        counts = {len(_split(ln, d)) for ln in sample}
        if len(counts) == 1 and counts.pop() > 1:
            return d
    return None


def _uncomment(line: str) -> str:
    """The line without a trailing '# comment'."""
    return line.split("#", 1)[0] if "#" in line else line


def _cells(line: str, delim: str | None) -> list[str]:
    """Cells of one line, without trailing empty cells (a trailing delimiter or tab)."""
    row = _split(line, delim)
    while row and not row[-1].strip():
        row.pop()
    return row


def sniff(path: Path) -> Layout:
    """Find delimiter, header, number style and first data row from the head of the file."""
    raw = _head_lines(path)
    numbered = [(i, ln) for i, ln in enumerate(raw) if ln.strip()]
    data = [(i, _uncomment(ln)) for i, ln in numbered if not ln.lstrip().startswith(COMMENTS)]
    data = [(i, ln) for i, ln in data if ln.strip()]
    if not data:
        raise FileFormatError(f"{path}: empty file (no data lines)")
    style = number_style([ln for _, ln in data[:21]], str(path))
    if not style.plain:
        data = [(i, style.fix()(ln)) for i, ln in data]
    delim = _delimiter([ln for _, ln in data[1:21]] or [data[0][1]])
    rows = [(i, _cells(ln, delim)) for i, ln in data[:3]]
    names, start = None, 0
    if len(rows) > 1 and len(rows[0][1]) == 1 and rows[0][1][0].strip().isdigit():
        start = 1  # PTS: a point count line before the data
    elif not all(_is_number(t) for t in rows[0][1]):
        names, start = [clean_name(t) for t in rows[0][1]], 1
    else:
        names = _comment_header(numbered, data[0][0], delim, len(rows[0][1]))
    if start >= len(rows):
        raise FileFormatError(f"{path}: header but no data rows")
    first_index, first_row = rows[start]
    return Layout(delim, names, first_index, len(first_row), first_row, style, start == 1
                  and names is None)


def _comment_header(numbered, first_data, delim, n_cols) -> list[str] | None:
    """Names from a comment line right before the data (CloudCompare's '//X,Y,Z'), if any."""
    before = [ln for i, ln in numbered if i < first_data]
    if not before:
        return None
    names = [clean_name(t) for t in _split(before[-1].lstrip("#/% "), delim)]
    return names if len(names) == n_cols and named_coordinates(names) else None


def choose_columns(layout: Layout, columns, path: Path) -> tuple[list[int], dict[str, list[int]]]:
    """Coordinate column indices and attribute columns for this layout."""
    if columns is not None:
        return explicit_columns(columns, layout.names, layout.n_cols, str(path)), {}
    if layout.names:
        coords = named_coordinates(layout.names)
        if coords is not None:
            return coords, named_attributes(layout.names)
    numeric = [i for i, t in enumerate(layout.first_row) if _is_number(t)]
    if len(numeric) < 2:
        raise FileFormatError(f"{path}: fewer than 2 numeric columns in the first data row")
    return numeric[:3], {}


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


def _read_fast(path: Path, layout: Layout, usecols: list[int]) -> tuple[np.ndarray, list[int]]:
    """numpy's C parser; raises ValueError on anything unusual (missing values, ragged rows)."""
    quoted = layout.delimiter is not None  # numpy allows quotes with one comment marker only
    options = {"delimiter": layout.delimiter, "quotechar": '"' if quoted else None,
               "usecols": usecols, "comments": "#" if quoted else COMMENTS, "ndmin": 2,
               "dtype": np.float64}
    counts: list[int] = []
    if layout.style.plain and not layout.pts:
        return np.loadtxt(path, skiprows=layout.skiprows, encoding="utf-8-sig", **options), counts
    with open(path, encoding="utf-8-sig") as fh:
        return np.loadtxt(_lines(fh, layout, counts), **options), counts


def _read_careful(path: Path, layout: Layout, usecols: list[int]) -> tuple[np.ndarray, list[int]]:
    """Line by line: missing values become NaN; a bad value is reported with its line."""
    out, counts = [], []
    first = 1 if layout.pts else layout.skiprows + 1
    with open(path, encoding="utf-8-sig", errors="replace") as fh:
        for lineno, line in enumerate(_lines(fh, layout, counts), first):
            if not line.strip() or line.lstrip().startswith(COMMENTS):
                continue
            row = _split(_uncomment(line), layout.delimiter)
            out.append(_parse_row(row, usecols, path, lineno))
    return np.array(out, dtype=np.float64).reshape(-1, len(usecols)), counts


def _pts_note(counts: list[int], n_rows: int) -> tuple[str, ...]:
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
        elif _is_number(cell):
            vals.append(float(cell))
        else:
            raise FileFormatError(f"{path}: non-numeric value {cell[:40]!r} at line {lineno}, "
                                  f"column {c + 1}")
    return vals


def read_text(path: Path, columns=None) -> tuple[np.ndarray, dict[str, np.ndarray], tuple]:
    """(n, d) coordinates, attributes and notes from a delimited text file."""
    return read_text_columns(path, columns)[:3]


def read_text_columns(path: Path, columns=None
                      ) -> tuple[np.ndarray, dict[str, np.ndarray], tuple, list[str] | None]:
    """read_text's result and the coordinate columns' header names (None without a header)."""
    layout = sniff(path)
    coords, attrs = choose_columns(layout, columns, path)
    usecols = coords + [c for cols in attrs.values() for c in cols]
    try:
        table, counts = _read_fast(path, layout, usecols)
    except ValueError:
        table, counts = _read_careful(path, layout, usecols)
    if len(table) == 0:
        raise FileFormatError(f"{path}: no data rows")
    points, pos = table[:, : len(coords)], len(coords)
    attributes = {}
    for name, cols in attrs.items():
        block = table[:, pos : pos + len(cols)]
        pos += len(cols)
        attributes[name] = _attribute(name, block)
    names = layout.names or [str(i + 1) for i in range(layout.n_cols)]
    note = f"coordinates from columns {', '.join(names[c] for c in coords)}"
    coord_names = [layout.names[c] for c in coords] if layout.names else None
    notes = (note, *layout.style.notes(), *_pts_note(counts, len(table)))
    return points, attributes, notes, coord_names


def _attribute(name: str, block: np.ndarray) -> np.ndarray:
    """Attribute array in its conventional dtype and shape."""
    if name == "colors":
        scale = 255.0 if np.nanmax(block, initial=0.0) <= 1.0 else 1.0
        return np.clip(np.nan_to_num(block * scale), 0, 255).astype(np.uint8)
    return block[:, 0] if block.shape[1] == 1 else block

"""Delimited text point files (XYZ, PTS, TXT, CSV): delimiter, header and column sniffing."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from core.errors import FileFormatError
from core.io.columns import clean_name, explicit_columns, named_attributes, named_coordinates
from core.io.numbers import number_style
from core.io.text_rows import COMMENTS, Layout, is_number, pts_note, read_rows, split, uncomment

SNIFF_BYTES = 1 << 16
DELIMITERS = (",", ";", "\t", "|")


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
        counts = {len(split(ln, d)) for ln in sample}
        if len(counts) == 1 and counts.pop() > 1:
            return d
    return None


def _cells(line: str, delim: str | None) -> list[str]:
    """Cells of one line, without trailing empty cells (a trailing delimiter or tab)."""
    row = split(line, delim)
    while row and not row[-1].strip():
        row.pop()
    return row


def sniff(path: Path) -> Layout:
    """Find delimiter, header, number style and first data row from the head of the file."""
    raw = _head_lines(path)
    numbered = [(i, ln) for i, ln in enumerate(raw) if ln.strip()]
    data = [(i, uncomment(ln)) for i, ln in numbered if not ln.lstrip().startswith(COMMENTS)]
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
    elif not all(is_number(t) for t in rows[0][1]):
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
    names = [clean_name(t) for t in split(before[-1].lstrip("#/% "), delim)]
    return names if len(names) == n_cols and named_coordinates(names) else None


def choose_columns(layout: Layout, columns, path: Path) -> tuple[list[int], dict[str, list[int]]]:
    """Coordinate column indices and attribute columns for this layout."""
    if columns is not None:
        return explicit_columns(columns, layout.names, layout.n_cols, str(path)), {}
    if layout.names:
        coords = named_coordinates(layout.names)
        if coords is not None:
            return coords, named_attributes(layout.names)
    numeric = [i for i, t in enumerate(layout.first_row) if is_number(t)]
    if len(numeric) < 2:
        raise FileFormatError(f"{path}: fewer than 2 numeric columns in the first data row")
    return numeric[:3], {}


def read_text(path: Path, columns=None) -> tuple[np.ndarray, dict[str, np.ndarray], tuple]:
    """(n, d) coordinates, attributes and notes from a delimited text file."""
    return read_text_columns(path, columns)[:3]


def read_text_columns(path: Path, columns=None, extra: tuple[str, ...] = ()
                      ) -> tuple[np.ndarray, dict[str, np.ndarray], tuple, list[str] | None]:
    """read_text's result and the coordinate columns' header names (None without a header).

    `extra` names header columns to read too, each as an attribute of its (cleaned) name.
    """
    layout = sniff(path)
    coords, attrs = choose_columns(layout, columns, path)
    for name in extra:
        if name not in attrs:
            attrs[name] = explicit_columns([name, name], layout.names, layout.n_cols,
                                           str(path))[:1]
    usecols = coords + [c for cols in attrs.values() for c in cols]
    table, counts = read_rows(path, layout, usecols)
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
    notes = (note, *layout.style.notes(), *pts_note(counts, len(table)))
    return points, attributes, notes, coord_names


def _attribute(name: str, block: np.ndarray) -> np.ndarray:
    """Attribute array in its conventional dtype and shape."""
    if name == "colors":
        scale = 255.0 if np.nanmax(block, initial=0.0) <= 1.0 else 1.0
        return np.clip(np.nan_to_num(block * scale), 0, 255).astype(np.uint8)
    return block[:, 0] if block.shape[1] == 1 else block

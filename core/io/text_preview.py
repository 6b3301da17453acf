"""The first rows of a text point file as the reader splits them, for an import dialog."""

from __future__ import annotations

import os
from pathlib import Path

from core.io.text import SNIFF_BYTES, Layout, sniff
from core.io.text_rows import COMMENTS, split, uncomment


def preview(path: str | os.PathLike, rows: int = 10) -> tuple[Layout, list[list[str]]]:
    """(layout, up to `rows` data rows split into cells) from the head of a text file.

    The layout is the reader's own (delimiter, header names, first data row); a file the
    reader refuses raises its FileFormatError here too.
    """
    path = Path(path)
    layout = sniff(path)
    with open(path, "rb") as fh:
        head = fh.read(SNIFF_BYTES).removeprefix(b"\xef\xbb\xbf")
    lines = head.decode("utf-8", errors="replace").splitlines()[layout.skiprows:]
    out: list[list[str]] = []
    for line in lines:
        if len(out) == rows:
            break
        if line.strip() and not line.lstrip().startswith(COMMENTS):
            cells = split(uncomment(line), layout.delimiter)
            if cells:
                out.append([cell.strip() for cell in cells])
    return layout, out

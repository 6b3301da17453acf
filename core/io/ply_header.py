"""The PLY header, parsed here (plyfile's parser is private API and refuses lines it does not
know, such as the 'bye' lines of Stanford's original range scans). Unknown lines become notes."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from core.errors import FileFormatError

MAX_HEADER_BYTES = 1 << 16  # a header is a few hundred bytes; give up well before reading data
PLY_TYPES = {
    "char": "i1", "uchar": "u1", "short": "i2", "ushort": "u2", "int": "i4", "uint": "u4",
    "float": "f4", "double": "f8", "int8": "i1", "uint8": "u1", "int16": "i2",
    "uint16": "u2", "int32": "i4", "uint32": "u4", "float32": "f4", "float64": "f8",
}
FORMATS = {"ascii": "", "binary_little_endian": "<", "binary_big_endian": ">"}


@dataclass(frozen=True)
class Property:
    """One property: a scalar of `dtype`, or a list (`count` dtype then `dtype` items)."""

    name: str
    dtype: np.dtype
    count: np.dtype | None = None


@dataclass
class Element:
    """An element (vertex, face...): its row count and properties in file order."""

    name: str
    n: int
    properties: list[Property] = field(default_factory=list)

    @property
    def has_lists(self) -> bool:
        return any(p.count is not None for p in self.properties)

    def row_dtype(self) -> np.dtype:
        """Structured dtype of one row (only for elements without lists)."""
        return np.dtype([(p.name, p.dtype) for p in self.properties])


@dataclass(frozen=True)
class Header:
    """Format ('' ascii, '<' or '>' binary), elements, comments, and notes on skipped lines."""

    byte_order: str
    elements: list[Element]
    comments: list[str]
    notes: list[str]

    @property
    def text(self) -> bool:
        return self.byte_order == ""


def _dtype(word: str, byte_order: str, where: str) -> np.dtype:
    if word not in PLY_TYPES:
        raise FileFormatError(f"{where}: bad PLY header: unknown property type {word!r}")
    return np.dtype((byte_order or "=") + PLY_TYPES[word])


def _raw_lines(fh, where: str) -> list[str]:
    """Header lines up to (not including) 'end_header'; the stream is left at the body."""
    if fh.readline(8).rstrip(b"\r\n") != b"ply":
        raise FileFormatError(f"{where}: not a PLY file: the first line must be 'ply'")
    lines, used = [], 4
    while used < MAX_HEADER_BYTES:
        raw = fh.readline(MAX_HEADER_BYTES - used)
        if not raw:
            break
        used += len(raw)
        line = raw.decode("ascii", "replace").strip()
        if line == "end_header":
            return lines
        lines.append(line)
    raise FileFormatError(f"{where}: bad PLY header: no 'end_header' line in the first "
                          f"{MAX_HEADER_BYTES // 1024} KB")


def parse_header(fh, where: str) -> Header:
    """Parse the header of an open binary stream positioned at the file's start."""
    lines = _raw_lines(fh, where)
    byte_order, elements, comments, skipped = None, [], [], []
    for line in lines:
        words = line.split()
        key = words[0] if words else ""
        try:
            if key == "format" and len(words) == 3 and words[1] in FORMATS:
                byte_order = FORMATS[words[1]]
            elif key == "comment":
                comments.append(line.partition(" ")[2])
            elif key == "obj_info":
                continue  # scanner settings (Cyberware): nothing for the points
            elif key == "element" and len(words) == 3:
                elements.append(Element(words[1], int(words[2])))
            elif key == "property" and elements and byte_order is not None:
                elements[-1].properties.append(_property(words, byte_order, where))
            elif key:
                skipped.append(line)
        except ValueError:
            raise FileFormatError(f"{where}: bad PLY header line {line[:60]!r}") from None
    if byte_order is None:
        raise FileFormatError(f"{where}: bad PLY header: no 'format' line before the elements")
    if any(e.n < 0 for e in elements):
        raise FileFormatError(f"{where}: bad PLY header: negative element count")
    notes = [f"PLY header: {len(skipped)} unknown line{'s' if len(skipped) > 1 else ''} "
             f"skipped ({', '.join(repr(s[:30]) for s in skipped[:3])})"] if skipped else []
    return Header(byte_order, elements, comments, notes)


def _property(words: list[str], byte_order: str, where: str) -> Property:
    """A 'property TYPE NAME' or 'property list COUNT_TYPE ITEM_TYPE NAME' line."""
    if len(words) == 5 and words[1] == "list":
        return Property(words[4], _dtype(words[3], byte_order, where),
                        _dtype(words[2], byte_order, where))
    if len(words) == 3:
        return Property(words[2], _dtype(words[1], byte_order, where))
    raise ValueError(words)

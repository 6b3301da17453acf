"""How numbers are written in a text point file: decimal commas, Fortran 'D' exponents, digit
grouping. Each style is either read exactly or refused with the reason; none is guessed.

- Decimal commas (`1,5 2,25 3,0`, or `1,5;2,25`) are read when another separator (spaces, tab,
  ';' or '|') splits every sampled line into numbers and no '.' appears in them.
- Fortran exponents (`1.5D+02`) are read as `1.5E+02`.
- Thousands separators (`1,234.5 2,0`, `1.234,5;2,0`, `"1,234.5"`) are refused: a grouped
  number such as `1,234` reads as 1.234 in half the world and 1234 in the other half.
"""

from __future__ import annotations

import re
from collections.abc import Callable
from dataclasses import dataclass

from core.errors import FileFormatError

CELL_SPLIT = re.compile(r"[ \t;|]+")
COMMA_DECIMAL = re.compile(r"^[+-]?\d*,\d+(?:[eEdD][+-]?\d+)?$")
INTEGER = re.compile(r"^[+-]?\d+$")
GROUPED = re.compile(r"^[+-]?\d{1,3}(?:,\d{3})+\.\d*$|^[+-]?\d{1,3}(?:\.\d{3})+,\d*$")
NUMBERISH = re.compile(r"^[+-]?[\d.,]*\d[\d.,]*(?:[eEdD][+-]?\d+)?$")
FORTRAN = re.compile(r"(?<=[\d.])[dD](?=[+-]?\d)")


@dataclass(frozen=True)
class NumberStyle:
    """Decimal comma and/or Fortran exponent; `fix` rewrites one line to plain float syntax."""

    decimal_comma: bool = False
    fortran: bool = False

    @property
    def plain(self) -> bool:
        return not (self.decimal_comma or self.fortran)

    def fix(self) -> Callable[[str], str]:
        """A line rewriter (decimal comma to point, D exponent to E)."""
        def rewrite(line: str) -> str:
            if self.fortran:
                line = FORTRAN.sub("E", line)
            return line.replace(",", ".") if self.decimal_comma else line
        return rewrite

    def notes(self) -> tuple[str, ...]:
        out = ("decimal commas read as decimal points",) if self.decimal_comma else ()
        return out + (("Fortran 'D' exponents read",) if self.fortran else ())


def _cells(line: str) -> list[str]:
    """Cells of a data line split on anything but commas (quotes removed); a comma ending a
    cell ("x, y, z" rows: a space after each comma) is a delimiter, not part of the number."""
    return [c.rstrip(",").strip("\"'") for c in CELL_SPLIT.split(line.strip())
            if c.rstrip(",")]


def _comma_delimited(line: str) -> bool:
    """True when a comma ends a cell of the line (commas delimit it: "1.5, 2.5, 3.5")."""
    return any(c.endswith(",") for c in CELL_SPLIT.split(line.strip()))


def number_style(lines: list[str], where: str) -> NumberStyle:
    """The style of the numeric data lines in `lines` (comments already removed)."""
    fortran = any(FORTRAN.search(c) and NUMBERISH.match(c)
                  for ln in lines for c in _cells(ln) + ln.split(","))
    split = [cells for cells in map(_cells, lines) if len(cells) > 1]  # ',' not the delimiter
    candidates = [c for cells in split for c in cells] + [c for ln in lines for c in _quoted(ln)]
    grouped = next((c for c in candidates if GROUPED.match(c)), None)
    if grouped is not None:
        raise FileFormatError(f"{where}: numbers with thousands separators ({grouped!r}) are "
                              "ambiguous (',' and '.' swap roles between countries); "
                              "write the file without digit grouping")
    rows = [_cells(ln) for ln in lines if any(ch.isdigit() for ch in ln)]
    rows = [r for r in rows if all(NUMBERISH.match(c) for c in r)]
    has_comma = any("," in c for r in rows for c in r)
    if not rows or not has_comma or any(len(r) < 2 for r in rows):
        return NumberStyle(fortran=fortran)
    delimiting = any(_comma_delimited(ln) for ln in lines)
    if not delimiting and all(COMMA_DECIMAL.match(c) or INTEGER.match(c) for r in rows for c in r):
        return NumberStyle(decimal_comma=True, fortran=fortran)
    if any(COMMA_DECIMAL.match(c) for r in rows for c in r):
        raise FileFormatError(f"{where}: ',' is used both as a decimal separator and otherwise "
                              "(e.g. with '.' decimals); cannot tell the numbers apart")
    return NumberStyle(fortran=fortran)


def _quoted(line: str) -> list[str]:
    """Contents of the double-quoted cells of a line ('"1,234.5"' in a CSV)."""
    return re.findall(r'"([^"]*)"', line)

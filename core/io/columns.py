"""Pick coordinate and attribute columns from a table header (names) or from the data alone."""

from __future__ import annotations

import re
from collections.abc import Sequence

from core.errors import FileFormatError

# (x names, y names, z names) per naming family, checked in order.
COORDINATE_NAMES = (
    (("x",), ("y",), ("z",)),
    (("lon", "lng", "long", "longitude"), ("lat", "latitude"),
     ("alt", "altitude", "elevation", "elev", "ele", "height", "z")),
    (("easting", "east"), ("northing", "north"),
     ("elevation", "elev", "ele", "height", "alt", "altitude", "z")),
)
ATTRIBUTE_NAMES = {
    "normals": (("nx", "normal_x", "normalx"), ("ny", "normal_y", "normaly"),
                ("nz", "normal_z", "normalz")),
    "colors": (("r", "red"), ("g", "green"), ("b", "blue")),
    "weights": (("w", "weight", "weights"),),
    "radius": (("radius", "radii", "r"),),
    "intensity": (("intensity", "i"),),
}


def clean_name(name: str) -> str:
    """Lower-case a header cell, dropping quotes, a leading '//' or '#', units and spaces."""
    name = re.sub(r"[\[(].*?[\])]", "", name.strip().strip("\"'"))  # 'X [m]', 'lat (deg)'
    return name.lstrip("/#").strip().lower()


def _find(names: list[str], options: Sequence[str]) -> int | None:
    """Index of the first header name among `options`, or None."""
    for opt in options:
        if opt in names:
            return names.index(opt)
    return None


def named_coordinates(names: list[str]) -> list[int] | None:
    """Coordinate column indices (2 or 3) from header names, or None if no family matches."""
    for xs, ys, zs in COORDINATE_NAMES:
        ix, iy = _find(names, xs), _find(names, ys)
        if ix is None or iy is None:
            continue
        iz = _find(names, zs)
        return [ix, iy] if iz is None else [ix, iy, iz]
    return None


def named_attributes(names: list[str]) -> dict[str, list[int]]:
    """Attribute name -> column indices, for every attribute whose columns are all present."""
    found = {}
    for attr, parts in ATTRIBUTE_NAMES.items():
        idx = [_find(names, opts) for opts in parts]
        if all(i is not None for i in idx):
            found[attr] = idx
    if "radius" in found and found["radius"][0] in found.get("colors", ()):
        del found["radius"]  # 'r' of an r, g, b colour triple
    return found


def parse_columns(columns: str | Sequence[str | int]) -> list[str | int]:
    """Normalize `columns` ('a,b,c', ['x', 'y'], [0, 1, 2]) to a list of names or indices."""
    items = columns.split(",") if isinstance(columns, str) else list(columns)
    out: list[str | int] = []
    for item in items:
        if isinstance(item, str):
            item = item.strip()
            out.append(int(item) if item.lstrip("-").isdigit() else clean_name(item))
        else:
            out.append(int(item))
    if len(out) not in (2, 3):
        raise FileFormatError(f"--columns needs 2 or 3 columns, got {len(out)}: {columns!r}")
    return out


def explicit_columns(
    columns: str | Sequence[str | int], names: list[str] | None, n_cols: int, path: str
) -> list[int]:
    """Resolve explicit column names/indices against the header, with a clear error."""
    try:
        items = parse_columns(columns)
    except FileFormatError as exc:
        raise FileFormatError(f"{path}: {exc}") from None
    out = []
    for item in items:
        if isinstance(item, int):
            if not -n_cols <= item < n_cols:
                raise FileFormatError(f"{path}: column {item} out of range (file has {n_cols})")
            out.append(item % n_cols)
        elif names is None or item not in names:
            have = ", ".join(names) if names else "no header"
            raise FileFormatError(f"{path}: no column named {item!r} ({have})")
        else:
            out.append(names.index(item))
    return out

"""Which column gives the points' weights (squared radii): a weight column as it is, or a
radius column squared, optionally after adding a probe radius to every radius."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from core.errors import FileFormatError
from core.io.columns import clean_name

MAX_RADIUS = float(np.sqrt(np.finfo(np.float64).max))  # larger radii have no float64 square

WEIGHT_ALIASES = ("weights", "weight", "w")
RADIUS_ALIASES = ("radius", "radii", "r")


def _column(attributes: dict[str, np.ndarray], name: str, aliases: tuple[str, ...],
            kind: str, path: Path) -> np.ndarray:
    """The (n,) float64 attribute called `name` (or its canonical alias), or an error."""
    key = clean_name(name)
    if key not in attributes and key in aliases:
        key = aliases[0]
    values = attributes.get(key)
    if values is None:
        have = ", ".join(sorted(attributes)) or "none"
        raise FileFormatError(f"{path}: no {kind} column {name!r} (attributes: {have})")
    values = np.asarray(values)
    if values.ndim != 1 or not np.issubdtype(values.dtype, np.number):
        raise FileFormatError(f"{path}: column {name!r} is not one number per point")
    return values.astype(np.float64)


def choose_weights(attributes: dict[str, np.ndarray], path: Path, *, weights: str | None = None,
                   radius: str | None = None, radius_add: float | None = None
                   ) -> tuple[dict[str, np.ndarray], str | None]:
    """(attributes with "weights" set to the chosen squared radii, or without it; a short
    description of where they came from, or None for unweighted points).

    Explicit `weights` / `radius` column names win; otherwise a `weights` attribute (columns
    weight, w) is used as it is, else a `radius` attribute (radius, r) squared. `radius_add`
    (a probe radius) is added to every radius first; with a weight column, radius = sqrt(w).
    """
    if weights is not None and radius is not None:
        raise FileFormatError("give either a weight column or a radius column, not both")
    if radius_add is not None and not (math.isfinite(radius_add) and radius_add >= 0):
        raise FileFormatError(f"--radius-add must be a finite radius >= 0, not {radius_add!r}")
    out = {k: v for k, v in attributes.items() if k not in ("weights", "radius")}
    if weights is not None or (radius is None and "weights" in attributes):
        name = weights or "weights"
        values, squared = _column(attributes, name, WEIGHT_ALIASES, "weight", path), True
        what = f"column {weights!r}" if weights else "the weight column (weight, w)"
        what += " as squared radii"
    elif radius is not None or "radius" in attributes:
        name = radius or "radius"
        values, squared = _column(attributes, name, RADIUS_ALIASES, "radius", path), False
        what = f"column {radius!r}" if radius else "the radius column (radius, r)"
        what += " squared"
    elif radius_add is not None:
        raise FileFormatError(f"{path}: --radius-add needs a radius or weight column")
    else:
        return out, None
    if radius_add:
        radii = _radii(values, path, name) if not squared else _roots(values, path, name)
        values, squared = _squared(radii + radius_add, path, name), True
        what += f", {radius_add:g} added to every radius"
    elif not squared:
        values = _squared(_radii(values, path, name), path, name)
    out["weights"] = values
    return out, what


def _squared(radii: np.ndarray, path: Path, name: str) -> np.ndarray:
    """The weights radii**2; a finite radius whose square overflows float64 is refused,
    named with its row (it is no NaN or infinity of the file's)."""
    with np.errstate(over="ignore"):
        weights = radii * radii
    over = np.isinf(weights) & np.isfinite(radii)
    if over.any():
        row = int(np.flatnonzero(over)[0])
        raise FileFormatError(f"{path}: radius {radii[row]:.6g} (column {name!r}, row {row}) "
                              f"is too large: its square, the weight, overflows float64 (radii "
                              f"up to {MAX_RADIUS:.3g} can be squared)")
    return weights


def _radii(values: np.ndarray, path: Path, name: str) -> np.ndarray:
    """Radii checked to be >= 0 where finite (non-finite rows are reported by the loader)."""
    if (values < 0).any():
        raise FileFormatError(f"{path}: column {name!r} has negative radii "
                              f"(the first in row {int(np.flatnonzero(values < 0)[0])})")
    return values


def _roots(weights: np.ndarray, path: Path, name: str) -> np.ndarray:
    """Radii sqrt(w) of weights, which must then be >= 0."""
    if (weights < 0).any():
        raise FileFormatError(f"{path}: --radius-add needs weights >= 0, but column {name!r} "
                              f"has negative ones (the first in row "
                              f"{int(np.flatnonzero(weights < 0)[0])})")
    return np.sqrt(weights)

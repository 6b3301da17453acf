"""How a query's alpha is given and checked: a radius `alpha` >= 0 or a squared `alpha2`.

One home for alpha validation: every query (AlphaComplex, topology, components) turns its
argument into the table's value here, and `threshold` is what that value is compared with.
"""

from __future__ import annotations

import numpy as np

from core.errors import InputError
from core.geometry.power import signed_sqrt

#: The largest float64: what an infinite alpha is compared with (see `threshold`).
LARGEST = float(np.finfo(np.float64).max)


def radius(alpha: object, signed: bool = False) -> float:
    """`alpha` as a float radius >= 0 (inf allowed); an InputError (a ValueError) otherwise.
    `signed` (a weighted table, whose values are signed radii): a finite negative alpha is
    taken as the table value it is (what optimal_alpha and the spectrum return there)."""
    try:
        value = float(alpha)  # type: ignore[arg-type]
    except (TypeError, ValueError):
        raise InputError(f"alpha must be a number (a radius), not {alpha!r}") from None
    if signed and value < 0 and value != -np.inf:
        return value
    if not value >= 0:
        raise InputError(f"alpha is a radius and must be >= 0, not {alpha!r}; pass a "
                         "squared value (which may be negative) as alpha2=")
    return value


def table_value(alpha: object = None, alpha2: object = None, signed: bool = False) -> float:
    """The table's value for a query given as exactly one of `alpha` (a radius >= 0; a
    signed radius for a `signed`, weighted, table) or `alpha2` (its square; any real,
    negative below zero radius): sign(a2) * sqrt(|a2|)."""
    if (alpha is None) == (alpha2 is None):
        raise InputError("give exactly one of alpha (a radius) and alpha2 (a squared radius), "
                         f"not {'both' if alpha is not None else 'neither'}")
    if alpha is not None:
        return radius(alpha, signed)
    try:
        value = float(alpha2)  # type: ignore[arg-type]
    except (TypeError, ValueError):
        raise InputError(f"alpha2 must be a number (a squared radius), not {alpha2!r}") from None
    if value != value:
        raise InputError("alpha2 must be a number (a squared radius), not NaN")
    return float(signed_sqrt(np.float64(value)))


def at_value(value: float) -> dict[str, float]:
    """Keyword arguments that make any query select the table value `value` (a spectrum
    entry, say): alpha=value where it is >= 0 (exact for every table), else alpha2=its
    signed square (weighted tables below zero radius)."""
    value = float(value)
    return {"alpha": value} if value >= 0 else {"alpha2": value * abs(value)}


def threshold(alpha: float) -> float:
    """The value a query at `alpha` compares the table with: +inf (the convex hull) is taken
    as the largest float. It is above every finite table value but below inf, which in the
    table means never (the `interior` of a simplex on the hull), so `value <= threshold`
    keeps hull simplices from turning interior, exactly as at any alpha past the spectrum."""
    return min(float(alpha), LARGEST)

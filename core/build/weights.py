"""Validation of point weights (squared radii) and how duplicate points' weights combine."""

from __future__ import annotations

import numpy as np

from core.errors import InputError


def as_weights(weights: object, n_points: int) -> np.ndarray | None:
    """(n,) float64 copy of `weights`, or None when absent or all zero (the classic complex).

    InputError for a wrong shape or NaN/infinite values.
    """
    if weights is None:
        return None
    try:
        w = np.array(weights, dtype=np.float64)
    except (TypeError, ValueError) as exc:
        raise InputError(f"weights must be numbers (squared radii): {exc}") from None
    if w.shape != (n_points,):
        raise InputError(f"weights must be one number per point, shape ({n_points},), "
                         f"got shape {w.shape}")
    bad = ~np.isfinite(w)
    if bad.any():
        raise InputError(f"{int(bad.sum())} weight(s) are NaN or infinite "
                         f"(first: row {int(np.flatnonzero(bad)[0])})")
    return None if not w.any() else w


def hide_light_duplicates(weights: np.ndarray, input_index: np.ndarray,
                          n_unique: int) -> tuple[np.ndarray, np.ndarray]:
    """Weights of the merged points and the input rows' vertex ids, -1 for hidden ones.

    Points at the same place keep the largest weight: a lighter ball there is inside the
    heavier one (hidden), equal ones are the same ball (merged, as classic duplicates).
    """
    merged = np.full(n_unique, -np.inf)
    np.maximum.at(merged, input_index, weights)
    hidden = weights < merged[input_index]
    return merged, np.where(hidden, -1, input_index)

"""Slider travel for weighted points (no Qt): their squared alphas start below zero, where a
log scale has no place, so the travel follows a symmetric log of alpha² (linear near zero).

Same interface as app.log_travel.LogTravel: position(index), index_at(position), page().
"""

from __future__ import annotations

import numpy as np

from app.log_travel import HIGH_QUANTILE, LOW_QUANTILE, TRAVEL, snap_index, sorted_quantile

PAGE_SHARE = 0.025  # a Page key moves this share of the travel


def symlog(values: np.ndarray, scale: float) -> np.ndarray:
    """sign(x) * log(1 + |x| / scale): monotone, linear near 0, logarithmic far from it."""
    return np.sign(values) * np.log1p(np.abs(values) / scale)


class SignedTravel:
    """Maps spectrum indexes (signed radii) to slider positions 0..TRAVEL and back, linear in
    the symmetric log of alpha² between a low and a high quantile of the spectrum."""

    def __init__(self, spectrum: np.ndarray, reach: float | None = None) -> None:
        """spectrum: (s,) float64 ascending signed radii; reach: a value (signed radius) the
        travel must include below its top end."""
        self.spectrum = np.asarray(spectrum, dtype=np.float64)
        squares = self.spectrum * np.abs(self.spectrum)
        size = np.abs(squares[(squares != 0) & np.isfinite(squares)])
        self.scale = float(np.quantile(size, 0.05)) if len(size) else 1.0
        self.keys = symlog(squares, self.scale)
        finite = self.keys[np.isfinite(self.keys)]  # ascending: symlog keeps the order
        low, high = ((sorted_quantile(finite, LOW_QUANTILE), sorted_quantile(finite, HIGH_QUANTILE))
                     if len(finite) else (0.0, 1.0))
        if reach is not None and np.isfinite(reach):
            high = max(high, float(symlog(np.array([2.0 * reach * abs(reach)]), self.scale)[0]))
        self.low, self.high = float(low), float(max(high, low + 1e-12))

    def position(self, index: int) -> int:
        """Slider position of spectrum[index]; the first index is 0, the last TRAVEL."""
        if index <= 0:
            return 0
        if index >= len(self.spectrum) - 1:
            return TRAVEL
        fraction = (self.keys[index] - self.low) / (self.high - self.low)
        return round(TRAVEL * float(np.clip(fraction, 0.0, 1.0)))

    def index_at(self, position: int) -> int:
        """Spectrum index a slider position shows (0 at the start, the hull at the end)."""
        if position <= 0:
            return 0
        if position >= TRAVEL:
            return len(self.spectrum) - 1
        key = self.low + (self.high - self.low) * position / TRAVEL
        return snap_index(self.keys, key)

    def page(self, index: int, up: bool) -> int:
        """Index after a Page key: a share of the travel up or down, at least one step."""
        step = PAGE_SHARE * (self.high - self.low)
        key = float(self.keys[index]) + (step if up else -step)
        target = snap_index(self.keys, key)
        target = max(target, index + 1) if up else min(target, index - 1)
        return int(np.clip(target, 0, len(self.spectrum) - 1))

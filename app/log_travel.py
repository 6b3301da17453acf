"""Where each critical alpha sits on the slider: travel in log alpha, not in rank (no Qt).

On real scans the useful alphas are the last few percent of the critical values, and the
largest (the hull's slivers) are orders of magnitude beyond anything worth seeing. So the
travel spans log alpha between a low and a high quantile of the spectrum; values outside
pile up at the ends (reachable with the arrow keys, which step one critical value).
"""

from __future__ import annotations

import numpy as np

TRAVEL = 10_000  # slider positions
PAGE_FACTOR = 1.25  # PageUp multiplies alpha by this, PageDown divides
LOW_QUANTILE, HIGH_QUANTILE = 0.001, 0.999  # the travel's ends, as quantiles of the spectrum


def snap_index(spectrum: np.ndarray, alpha: float) -> int:
    """Index of the largest critical alpha <= alpha (the shape at alpha is the shape there)."""
    return max(int(np.searchsorted(spectrum, alpha, side="right")) - 1, 0)


def sorted_quantile(values: np.ndarray, q: float) -> float:
    """np.quantile(values, q) (linear interpolation) of (n,) ascending values, n >= 1, read
    off by index: no sort or copy of a spectrum of millions when a dataset opens."""
    position = q * (len(values) - 1)
    below = int(np.floor(position))
    above = min(below + 1, len(values) - 1)
    low, high = float(values[below]), float(values[above])
    return low + (high - low) * (position - below)


class LogTravel:
    """Maps spectrum indexes to slider positions 0..TRAVEL and back, linear in log alpha."""

    def __init__(self, spectrum: np.ndarray, reach: float | None = None) -> None:
        """spectrum: (s,) float64 ascending; reach: an alpha the travel must include (the
        optimal one, say) below the top end."""
        self.spectrum = np.asarray(spectrum, dtype=np.float64)
        positive = self.spectrum[np.searchsorted(self.spectrum, 0.0, side="right"):]  # a view
        if len(positive) == 0:
            positive = np.ones(1)
        low, high = sorted_quantile(positive, LOW_QUANTILE), sorted_quantile(positive,
                                                                             HIGH_QUANTILE)
        if reach is not None and np.isfinite(reach) and reach > 0:
            high = max(high, 2.0 * reach)
        high = max(min(high, positive[-1]), low * 1.0001)
        self.log_low, self.log_high = float(np.log(low)), float(np.log(high))

    def position(self, index: int) -> int:
        """Slider position of spectrum[index]; the first index is 0, the last TRAVEL."""
        if index <= 0:
            return 0
        if index >= len(self.spectrum) - 1:
            return TRAVEL
        return round(TRAVEL * self._fraction(self.spectrum[index]))

    def _fraction(self, alpha: float) -> float:
        """Where alpha lies between the travel's ends on a log scale, clipped to 0..1."""
        if alpha <= 0:
            return 0.0
        fraction = (np.log(alpha) - self.log_low) / (self.log_high - self.log_low)
        return float(np.clip(fraction, 0.0, 1.0))

    def index_at(self, position: int) -> int:
        """Spectrum index a slider position shows (0 at the start, the hull at the end)."""
        if position <= 0:
            return 0
        if position >= TRAVEL:
            return len(self.spectrum) - 1
        log_alpha = self.log_low + (self.log_high - self.log_low) * position / TRAVEL
        return snap_index(self.spectrum, float(np.exp(log_alpha)))

    def page(self, index: int, up: bool) -> int:
        """Index after a Page key: alpha times (up) or over PAGE_FACTOR, snapped to the critical
        value at or below, and at least one critical value from index."""
        alpha = float(self.spectrum[index])
        if alpha <= 0:
            target = index + 1 if up else index - 1
        else:
            target = snap_index(self.spectrum, alpha * PAGE_FACTOR if up else alpha / PAGE_FACTOR)
            target = max(target, index + 1) if up else min(target, index - 1)
        return int(np.clip(target, 0, len(self.spectrum) - 1))

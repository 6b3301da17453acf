"""Numbers for people: digits relative to the data's extent, units, plurals (no Qt)."""

from __future__ import annotations

import math


def plural(count: int, singular: str, many: str | None = None) -> str:
    """'1 point', '2 points', '1,234 vertices' (many: the irregular plural)."""
    return f"{count:,} {singular if count == 1 else (many or singular + 's')}"


def decimals_for(resolution: float) -> int:
    """Digits after the point that show differences of `resolution` (>= 0 digits)."""
    if not (resolution > 0 and math.isfinite(resolution)):
        return 0
    return max(0, -math.floor(math.log10(resolution)))


def coordinate(value: float, extent: float, digits: int = 4) -> str:
    """A coordinate shown to about 1/10**digits of the data's extent: a LiDAR box at 4.9e6
    prints '4918340.12', not '4.91834e+06'. Tiny or huge magnitudes fall back to e-notation."""
    if not math.isfinite(value):
        return str(value)
    if extent > 0 and math.isfinite(extent):
        places = decimals_for(extent / 10**digits)
        if abs(value) < 1e15 and places <= 12:
            return f"{value:.{places}f}"
    return f"{value:.6g}"


def quantity(value: float, digits: int = 4) -> str:
    """A length, area or count-like measure with `digits` significant digits, no e-notation
    between 1e-4 and 1e9 ('0.00110545' -> '0.001105', '4918339.5' -> '4918340')."""
    if not math.isfinite(value) or value == 0:
        return f"{value:g}"
    magnitude = math.floor(math.log10(abs(value)))
    if -4 <= magnitude < 9:
        places = max(0, digits - 1 - magnitude)
        return f"{round(value, places):,.{places}f}"
    return f"{value:.{digits - 1}e}"


def with_unit(text: str, unit: str | None, power: int = 1) -> str:
    """'12.5 m', '3.1 m²' ('12.5' when the unit is unknown)."""
    if not unit:
        return text
    return f"{text} {unit}{'' if power == 1 else {2: '²', 3: '³'}[power]}"

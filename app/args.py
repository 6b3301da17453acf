"""Command-line value checks shared by the window's options and the `info`/`export` subcommands."""

from __future__ import annotations

import argparse
import math


def radius(text: str) -> float:
    """A finite alpha radius >= 0 (NaN, negative values and infinity are refused).

    Infinity is refused in both entry points alike: the convex hull is the largest critical
    alpha (`--alpha` above it shows the hull), and an infinite alpha has no JSON form.
    """
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"alpha must be a number, not {text!r}") from None
    if value < 0.0 and math.isfinite(value):
        raise argparse.ArgumentTypeError(
            f"alpha must be a radius >= 0, not {text!r}; for a squared value (which may be "
            "negative with weights) use --alpha2")
    if not (value >= 0.0 and math.isfinite(value)):
        raise argparse.ArgumentTypeError(f"alpha must be a finite radius >= 0, not {text!r}")
    return value


def squared_radius(text: str) -> float:
    """A finite squared alpha (any sign: weighted points enter below zero)."""
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"alpha2 must be a number, not {text!r}") from None
    if not math.isfinite(value):
        raise argparse.ArgumentTypeError(f"alpha2 must be a finite number, not {text!r}")
    return value


def probe_radius(text: str) -> float:
    """A finite radius >= 0 to add to every point's radius."""
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a radius, not {text!r}") from None
    if not (value >= 0.0 and math.isfinite(value)):
        raise argparse.ArgumentTypeError(f"expected a finite radius >= 0, not {text!r}")
    return value

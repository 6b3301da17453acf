"""Command-line values shared by the window's options and the `info`/`export` subcommands:
their checks (radii, counts, mode parameters) and the mode options."""

from __future__ import annotations

import argparse
import math
import sys

#: The largest radius to add (probe, --radius-add): the sum with any atom or point radius
#: must still have a float64 square.
MAX_ADDED_RADIUS = math.sqrt(sys.float_info.max) / 2


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


def negative_values_joined(argv: list[str]) -> list[str]:
    """argv with each '--option -1e-3' written '--option=-1e-3': argparse takes a value
    that starts with '-' for an option unless it looks like '-1' or '-.5', so negative
    numbers with an exponent ('--alpha2 -1e-3') failed to parse."""
    out: list[str] = []
    for i, arg in enumerate(argv):
        if (out and out[-1].startswith("--") and "=" not in out[-1] and arg.startswith("-")
                and _is_number(arg) and argv[i - 1] == out[-1]):
            out[-1] = f"{out[-1]}={arg}"
        else:
            out.append(arg)
    return out


def _is_number(text: str) -> bool:
    try:
        float(text)
    except ValueError:
        return False
    return True


def neighbour_count(text: str) -> int:
    """A whole number of neighbours, 1..1000."""
    if not text.isdigit() or not 1 <= int(text) <= 1000:
        raise argparse.ArgumentTypeError(f"K must be a whole number 1..1000, not {text!r}")
    return int(text)


def compression(text: str) -> float:
    """An anisotropy factor tau in [0, 1) (0 = classic)."""
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"TAU must be a number, not {text!r}") from None
    if not 0.0 <= value < 1.0:
        raise argparse.ArgumentTypeError(f"TAU must be in [0, 1) (0 = classic), not {text!r}")
    return value


def add_mode_options(parser: argparse.ArgumentParser) -> None:
    """--density K [--combine mean|max], --anisotropic TAU [--normals estimate|file]."""
    group = parser.add_argument_group("alpha modes (Teichmann & Capps 1998; see README)")
    group.add_argument("--density", type=neighbour_count, metavar="K",
                       help="density-scaled alpha: radii divided by the distance to the K-th "
                            "nearest neighbour (alpha in local spacings)")
    group.add_argument("--combine", choices=("mean", "max"),
                       help="how a simplex combines its vertices' spacings (default mean)")
    group.add_argument("--anisotropic", type=compression, metavar="TAU",
                       help="anisotropic alpha: the ball compressed along the surface normal "
                            "to 1-TAU of its radius, TAU in [0, 1)")
    group.add_argument("--normals", choices=("estimate", "file"),
                       help="normals for --anisotropic: estimated by PCA (default) or the file's")


def mode_of(args: argparse.Namespace):
    """The core.modes.alpha_modes.Mode the options ask for; ValueError for options that need
    another."""
    from core.modes.alpha_modes import make_mode

    if args.combine is not None and args.density is None:
        raise ValueError("--combine needs --density K")
    if args.normals is not None and args.anisotropic is None:
        raise ValueError("--normals needs --anisotropic TAU")
    return make_mode(args.density, args.combine or "mean", args.anisotropic or 0.0,
                     args.normals == "file")


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
    if value > MAX_ADDED_RADIUS:
        raise argparse.ArgumentTypeError(
            f"{text!r} is too large: radii are squared into weights, and float64 squares "
            f"radii up to about {MAX_ADDED_RADIUS:.3g} only")
    return value


def count(text: str) -> int:
    """A positive whole number (a point count, a number of components)."""
    if not text.isdigit() or int(text) < 1:
        raise argparse.ArgumentTypeError(f"expected a positive whole number, not {text!r}")
    return int(text)

"""What an exported shape carries about itself: alpha, source, counts, measure, Betti numbers."""

from __future__ import annotations

import json
import math
import os
from importlib import metadata as importlib_metadata

import numpy as np


def software() -> str:
    """'alphascoop <version>' (the installed distribution, else the source tree)."""
    try:
        return f"alphascoop {importlib_metadata.version('alphascoop')}"
    except importlib_metadata.PackageNotFoundError:
        return "alphascoop (source tree)"


def betti_numbers(ac, alpha: float) -> list[int] | None:
    """Betti numbers at alpha if the complex offers them (`ac.betti`), else None. A negative
    alpha (a weighted table's signed radius) is asked for as its signed square."""
    betti = getattr(ac, "betti", None)
    if betti is None:
        return None
    try:
        if not callable(betti):
            values = betti
        elif alpha < 0:
            values = betti(alpha2=alpha * abs(alpha))
        else:
            values = betti(alpha)
        return [int(b) for b in np.asarray(values).ravel()]
    except (TypeError, ValueError):
        return None


def mode_metadata(ac) -> dict:
    """The alpha mode the table was built in (core.modes.alpha_modes; classic when `ac` has
    none)."""
    mode = getattr(ac, "mode", None)
    return {"name": "classic"} if mode is None else mode.to_dict()


def squared(alpha: float) -> float | None:
    """alpha² as a float (signed, alpha * |alpha|, for a weighted table's negative values), or
    None where it overflows float64 (alpha above ~1.34e154: any such alpha gives the convex
    hull, and JSON has no infinity)."""
    value = float(alpha) * abs(float(alpha))  # float products give inf, never OverflowError
    return value if math.isfinite(value) else None


def shape_metadata(ac, shape, source: str | os.PathLike | None = None) -> dict:
    """JSON-ready facts about `shape` (an AlphaShape of `ac`) for file headers and sidecars."""
    meta = {
        "software": software(),
        "alpha": float(shape.alpha) if math.isfinite(shape.alpha) else None,  # inf: hull
        "alpha_sq": squared(shape.alpha),
        "source": None if source is None else os.fspath(source),
        "mode": mode_metadata(ac),
        "dim": int(ac.dim),
        "ambient_dim": int(ac.ambient_dim),
        "n_points": len(ac.points),
        "n_cells": len(shape.cells),
        "n_regular_facets": len(shape.regular_facets),
        "n_singular": [len(shape.singular(k)) for k in range(ac.dim)],
        "volume" if ac.dim == 3 else "area": float(shape.measure),
    }
    if getattr(ac, "weights", None) is not None:  # weighted: values are squared radii
        meta["weighted"] = True
        meta["alpha2"] = shape.alpha2 if math.isfinite(shape.alpha2) else None
        meta["alpha_sq"] = meta["alpha2"]
        meta["hidden_points"] = int((np.asarray(ac.input_index) < 0).sum())
    if ac.dim < ac.ambient_dim:  # planar 3D input: 2D outputs are in the plane's frame
        origin = np.asarray(ac.to_ambient(np.zeros((1, ac.dim))))[0]
        axes = np.asarray(ac.to_ambient(np.eye(ac.dim))) - origin
        meta["plane_origin"] = origin.tolist()
        meta["plane_axes"] = axes.tolist()
    betti = betti_numbers(ac, shape.alpha)
    if betti is not None:
        meta["betti"] = betti
    return meta


def comment_lines(meta: dict) -> list[str]:
    """'key=value' lines for formats with free-text comments (PLY, OBJ)."""
    return [f"{key}={json.dumps(value)}" for key, value in meta.items()]


def sidecar_text(meta: dict) -> str:
    """The JSON sidecar's content."""
    return json.dumps(meta, indent=2, sort_keys=False) + "\n"

"""Colour by (no Qt, no VTK): which modes a dataset offers and the value of each drawn cell or
point in each mode. Style only: the values are read from the table and the shape already
queried, never a new geometry query.

Modes: the class (each layer its own colour), the alpha at which each simplex enters (log
scale), the solid component at the current alpha, and the point attributes the reader loaded
(RGB colours, intensity, classification, ...).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from core.topology.components import facet_labels, solid_labels

CELL_LAYERS = ("surface", "boundary", "interior", "singular_highlight", "singular_edges",
               "singular_points")
FACET_LAYERS = ("surface", "boundary")  # facets beside a cell (3D surface, 2D boundary)
MAX_CATEGORIES = 20


@dataclass(frozen=True)
class ColourMode:
    """A way to colour the layers: its key, menu title, and what it colours.

    `source` is None (class colours), "cells" (one value per drawn simplex, changes with
    alpha) or "points" (one value per point, fixed); `rgb` marks direct (m, 3) uint8 colours.
    """

    key: str
    title: str
    source: str | None = None
    log: bool = False
    categorical: bool = False
    rgb: bool = False


CLASS = ColourMode("class", "Class (layer colours)")
ENTER = ColourMode("enter", "Alpha at which it appears", "cells", log=True)
COMPONENT = ColourMode("component", "Solid component", "cells", categorical=True)


def attribute_mode(name: str, values: np.ndarray) -> ColourMode | None:
    """The mode for a point attribute, or None when it cannot be shown as a colour."""
    values = np.asarray(values)
    if name == "colors" and values.ndim == 2 and values.shape[1] >= 3:
        return ColourMode(f"attribute:{name}", "RGB colours", "points", rgb=True)
    if values.ndim != 1 or not np.issubdtype(values.dtype, np.number):
        return None
    few = np.issubdtype(values.dtype, np.integer) and \
        len(np.unique(values[:100_000])) <= MAX_CATEGORIES
    categorical = name == "classification" or few
    return ColourMode(f"attribute:{name}", name.capitalize(), "points",
                      categorical=bool(categorical))


def modes_for(attributes: dict[str, np.ndarray]) -> list[ColourMode]:
    """Every mode a dataset with these per-point attributes offers, class first."""
    extra = [attribute_mode(name, values) for name, values in sorted(attributes.items())]
    return [CLASS, ENTER, COMPONENT, *[mode for mode in extra if mode is not None]]


def layer_rows(shape, name: str) -> tuple[int, np.ndarray] | None:
    """(k, rows of simplices(k)) drawn by the named layer, in the layer's cell order (the
    shape's id arrays are aligned with the arrays the scene draws); None for other layers."""
    dim = shape.dim
    if name == "interior":
        return dim, shape.cell_ids
    if name == "boundary":
        return dim - 1, shape.regular_facet_ids
    if name == "surface":  # the scene's 3D surface: regular then singular triangles
        return dim - 1, np.concatenate([shape.regular_facet_ids, shape.singular_ids(dim - 1)])
    order = {"singular_points": 0, "singular_edges": 1, "singular_highlight": 2}.get(name)
    if order is None or order >= dim:
        return None
    return order, shape.singular_ids(order)


def cell_values(mode: ColourMode, ac, shape, name: str,
                labels: np.ndarray | None = None) -> np.ndarray | None:
    """(c,) float64 value of each simplex the named layer draws (nan = no value), or None when
    the mode does not colour that layer. `labels`: solid_labels at the shape's alpha."""
    found = layer_rows(shape, name)
    if found is None or mode.source != "cells":
        return None
    k, rows = found
    if mode is ENTER or mode.key == ENTER.key:
        return np.take(ac.intervals(k)[:, 0], rows)
    labels = solid_labels(ac, shape.alpha) if labels is None else labels
    if k == ac.dim:
        values = np.take(labels, rows).astype(np.float64)
    elif k == ac.dim - 1 and name in FACET_LAYERS:
        values = facet_labels(ac, rows, labels).astype(np.float64)
    else:
        return np.full(len(rows), np.nan)
    values[values < 0] = np.nan
    return values % MAX_CATEGORIES


def point_values(mode: ColourMode, attributes: dict[str, np.ndarray]) -> np.ndarray:
    """(m,) float64 or, for RGB, (m, 3) uint8 values of a point mode, aligned with ac.points."""
    values = np.asarray(attributes[mode.key.split(":", 1)[1]])
    if mode.rgb:
        return np.ascontiguousarray(values[:, :3], dtype=np.uint8)
    return values.astype(np.float64)


def value_range(mode: ColourMode, values: np.ndarray, alpha: float,
                spectrum: np.ndarray) -> tuple[float, float]:
    """The colour bar's range: the 2nd percentile of the shown alphas to the current one
    (enter: most of a scan's surface enters within a small factor of alpha), 0..19
    (categories), or the 1st-99th percentile (other attributes)."""
    if mode.log:
        positive = values[np.isfinite(values) & (values > 0)]
        if len(positive) == 0:
            positive = spectrum[spectrum > 0]
        low = float(np.percentile(positive, 2)) if len(positive) else 1.0
        return low, max(float(alpha), low * 1.01)
    if mode.categorical:
        finite = values[np.isfinite(values)]
        high = float(finite.max()) if len(finite) else 0.0
        return 0.0, max(min(high, MAX_CATEGORIES - 1.0), 1.0)
    finite = values[np.isfinite(values)]
    if len(finite) == 0:
        return 0.0, 1.0
    low, high = (float(v) for v in np.percentile(finite, (1, 99)))
    return (low, high) if high > low else (low, low + 1.0)


"""Builds the interval table: for every Delaunay simplex, the alphas where it enters the
complex (enter), becomes a face of a higher simplex (regular) and turns interior (interior).

Rules (CGAL's GENERAL mode; ARCHITECTURE.md): a cell enters at its circumradius; a face enters
at its smallest circumradius unless attached (a cofacet's vertex strictly inside that sphere),
then with its first cofacet; regular = smallest enter among cofacets; interior = largest enter
among the cells around it, inf on the convex hull. Each level is returned sorted by enter.

Weighted points (weights = squared radii) use the same rules with orthogonal spheres and power
distance (core.geometry.power); their values are signed radii sign(p) * sqrt(|p|) of the powers p,
so every comparison is the same as on powers, and vertices enter at -sqrt(w) (or, attached, with
their first edge).

The passes, one module each: the cells (core.build.table_cells, with core.build.folds), the
facets (core.build.table_facets), the edges of a 3D table (core.build.table_edges) and the
vertices (core.build.table_vertices); each level is sorted by core.build.sorting.
"""

from __future__ import annotations

import numpy as np

from core.build.cell_pass import CellSpheres
from core.build.levels import Table
from core.build.table_cells import cell_level
from core.build.table_edges import edge_level
from core.build.table_facets import facet_level
from core.build.table_vertices import vertex_level
from core.progress import Progress


def build_table(points: np.ndarray, cells: np.ndarray, neighbors: np.ndarray,
                progress: Progress | None = None, weights: np.ndarray | None = None,
                exact: bool = True, spheres: CellSpheres | None = None, *,
                sort: bool = True, radii: bool = True, mirror: np.ndarray | None = None
                ) -> Table:
    """The interval table of the Delaunay cells of `points` ((m, d) float64, well scaled).

    With (m,) `weights` (squared radii >= 0, same scale), the cells are the regular
    triangulation's and the values signed radii of powers (module docstring). `exact`: the
    classic table's doubtful sign decisions and ill-conditioned radii are made exact
    (core/build/table_signs.py); False keeps the floating-point ones. `spheres`: the classic
    cells' spheres from the certification's shared pass (core.build.cell_pass), consumed.

    For an alpha mode (core/modes/alpha_modes.py), which supplies its own values and sorts once by
    them: sort=False keeps every level in the order it was built (ids consistent; no
    facet_interior_order), and radii=False (with sort=False) computes no values for the
    faces (their enter, regular and interior are (0,) arrays: the mode computes its own
    from the structure; the cells keep their classic values). `mirror`:
    (t, d+1) int8, each neighbour's column that holds the cell (core.build.delaunay.Triangulation),
    when known: saves finding it by a random gather of the neighbours' rows."""
    if sort and not radii:
        raise ValueError("radii=False is for an unsorted table (sort=False)")
    def step(fraction: float, stage: str) -> None:
        if progress is not None:
            progress(fraction, stage)

    d = points.shape[1]
    step(0.0, "circumspheres of cells")
    exact_counts: list[int] | None = [] if exact else None
    top, neighbors, det, bits, measure, mirror = cell_level(points, cells, neighbors, weights,
                                                        exact_counts, spheres, sort, mirror)
    step(0.2, "facets")
    facets, facet_cells, flip, near_flat, obtuse = facet_level(points, top, neighbors, det, bits,
                                                           weights, exact_counts, sort, radii,
                                                           mirror)
    del neighbors, mirror
    levels = [facets, top]
    edge_bits = None
    if d == 3:
        step(0.55, "edges")
        edges, edge_bits = edge_level(points, facets, near_flat, obtuse, weights, sort)
        levels.insert(0, edges)
    step(0.9, "vertices")
    levels.insert(0, vertex_level(len(points), levels[0], points, weights, edge_bits))
    # a sorted table's facet order by interior is sorted on first use (Table)
    by_interior = None if sort else np.empty(0, dtype=np.int32)
    step(1.0, "done")
    return Table(levels, facet_cells, flip, measure, by_interior, sum(exact_counts or []))

"""build_table's mode path (sort=False, radii=False): the same simplices, adjacency and
cells' values as the classic sorted table, only in the order they were built (and no
values for the faces)."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.spatial import Delaunay

from core.build.levels import Table
from core.build.table import build_table


def _table(points: np.ndarray, **kwargs) -> Table:
    tri = Delaunay(points)
    order = np.argsort(tri.simplices, axis=1)  # rows ascending, neighbours kept opposite
    cells = np.take_along_axis(tri.simplices, order, axis=1).astype(np.int32)
    neighbors = np.take_along_axis(tri.neighbors, order, axis=1).astype(np.int32)
    return build_table(points, cells, neighbors, **kwargs)


def _by_simplex(table: Table, k: int, columns: tuple[str, ...]) -> dict[tuple, tuple]:
    """Every simplex of level k -> the named values, its facets (as vertex tuples) and, for
    facets, its cells (as vertex tuples)."""
    levels = table.levels
    level = levels[k]
    out = {}
    for row, simplex in enumerate(level.simplices):
        values = tuple(float(getattr(level, c)[row]) for c in columns)
        faces = () if k == 0 else tuple(sorted(
            tuple(levels[k - 1].simplices[f]) for f in level.face_ids[row]))
        cells = ()
        if k == len(levels) - 2:
            cells = tuple(sorted(tuple(levels[-1].simplices[c]) for c in table.facet_cells[row]
                                 if c >= 0))
        out[tuple(simplex)] = (values, faces, cells)
    return out


def _outward(table: Table) -> dict[tuple, tuple]:
    """Every facet -> the cell (vertex tuple) its orientation faces out of (facet_flip is
    relative to facet_cells[:, 0], which depends on the cells' order)."""
    cells = table.levels[-1].simplices
    out = {}
    for facet, pair, flip in zip(table.levels[-2].simplices, table.facet_cells,
                                 table.facet_flip, strict=True):
        away = pair[0] if not flip or pair[1] < 0 else pair[1]
        out[tuple(facet)] = (tuple(cells[away]), bool(flip) if pair[1] < 0 else None)
    return out


@pytest.mark.parametrize("dim", [2, 3])
@pytest.mark.parametrize("kind", ["uniform", "grid", "jittered lattice"])
def test_unsorted_table_is_the_sorted_one_in_another_order(dim, kind):
    rng = np.random.default_rng(dim)
    if kind == "grid":  # cospherical, flat cells
        points = rng.integers(-3, 4, (150, dim)).astype(float)
    elif kind == "jittered lattice":  # float signs in doubt: the cells' exact decisions count
        axes = np.meshgrid(*[np.arange(6.0)] * dim, indexing="ij")
        points = np.column_stack([a.ravel() for a in axes])
        points += rng.normal(size=points.shape) * 1e-12
    else:
        points = rng.uniform(-1, 1, (300, dim))
    points = np.unique(points, axis=0)
    classic = _table(points)
    unsorted = _table(points, sort=False)
    structure = _table(points, sort=False, radii=False)
    assert len(unsorted.facet_interior_order) == 0
    everything = ("enter", "regular", "interior")
    for k in range(dim + 1):
        want = _by_simplex(classic, k, everything)
        assert _by_simplex(unsorted, k, everything) == want
        # without values for the faces (a mode computes its own): the structure, and the
        # cells' values
        named = everything if k == dim else ()
        got = _by_simplex(structure, k, named)
        assert got == {s: (v if k == dim else (), f, c) for s, (v, f, c) in want.items()}
        if k < dim:
            level = structure.levels[k]
            assert all(len(v) == 0 for v in (level.enter, level.regular, level.interior))
    assert _outward(structure) == _outward(classic)
    measure = dict(zip(map(tuple, classic.levels[-1].simplices), classic.cell_measure,
                       strict=True))
    assert all(measure[tuple(s)] == m for s, m in zip(structure.levels[-1].simplices,
                                                      structure.cell_measure, strict=True))


def test_a_sorted_table_needs_its_radii():
    with pytest.raises(ValueError, match="radii=False"):
        _table(np.random.default_rng(0).uniform(size=(20, 2)), radii=False)


@pytest.mark.parametrize("weighted", [False, True])
def test_sorted_table_sorts_its_facets_by_interior_on_first_use(weighted):
    """A sorted build leaves the facets' order by interior unsorted (a molecule's measures
    never ask for it); its first use sorts it: the stable order of the interiors (hull
    facets, inf, last), read-only, kept."""
    from core.complex import AlphaComplex

    rng = np.random.default_rng(3)
    points = rng.uniform(-1, 1, (400, 3))
    weights = rng.uniform(0.0, 0.01, 400) if weighted else None
    ac = AlphaComplex.from_points(points, weights=weights)
    table = ac.index.table
    assert table.facet_order is None
    order = table.facet_interior_order
    np.testing.assert_array_equal(order, np.argsort(table.levels[2].interior, kind="stable"))
    assert order.dtype == np.int32 and not order.flags.writeable
    assert table.facet_interior_order is order
    for alpha in np.quantile(ac.spectrum(), [0.2, 0.5, 0.99]):  # both ways of finding them
        facets = table.levels[2]
        boundary = (facets.enter <= alpha) & (facets.interior > alpha)
        np.testing.assert_array_equal(ac.shape(alpha=float(alpha)).boundary_facets,
                                      facets.simplices[boundary])

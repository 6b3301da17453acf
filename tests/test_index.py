"""The public TableIndex (core/query/index.py): frozen, read-only, and facets it orients face out
of their cell (checked against the cells' geometry, not against our own orientation code)."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

import core.topology.betti
from core import AlphaComplex
from core.query.index import TableIndex, oriented_facets


@pytest.fixture(scope="module", params=[2, 3])
def ac(request) -> AlphaComplex:
    dim = request.param
    return AlphaComplex.from_points(np.random.default_rng(dim).random((150, dim)))


def test_the_index_is_frozen_and_its_arrays_read_only(ac):
    index = ac.index
    with pytest.raises(dataclasses.FrozenInstanceError):
        index.table = None
    arrays = [index.oriented_facets, index.facet_cell0, *index.facets_by_interior,
              index.cumulative_measure, index.spectrum(), index.facet_cells()]
    for k in range(ac.dim + 1):
        arrays += [index.simplices(k), index.intervals(k)]
    assert not any(arr.flags.writeable for arr in arrays)


def test_oriented_facets_face_out_of_their_cell(ac):
    index, dim = ac.index, ac.dim
    cells = index.simplices(dim)
    rows = oriented_facets(index.simplices(dim - 1), index.table.facet_flip)
    for side in (0, 1):
        cell = index.facet_cells()[:, side]
        real = cell >= 0
        facets = rows[side::2][real]
        corners = ac.points[facets]
        opposite = ac.points[[next(iter(set(c) - set(f))) for c, f in
                              zip(cells[cell[real]].tolist(), facets.tolist(), strict=True)]]
        if dim == 3:  # the normal (b-a)x(c-a) points away from the cell's fourth vertex
            normal = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
            side_of = np.einsum("ij,ij->i", normal, opposite - corners[:, 0])
            assert np.all(side_of < 0)
        else:  # the cell lies left of a->b
            edge, to_third = corners[:, 1] - corners[:, 0], opposite - corners[:, 0]
            assert np.all(edge[:, 0] * to_third[:, 1] - edge[:, 1] * to_third[:, 0] > 0)


def test_a_known_spectrum_is_used_as_given(ac):
    spectrum = np.array(ac.spectrum())
    index = TableIndex(ac.index.table, weighted=False, known_spectrum=spectrum)
    assert index.spectrum() is spectrum and not spectrum.flags.writeable


def test_signatures_are_explicit_and_come_back_with_a_saved_table(ac, tmp_path, monkeypatch):
    fresh = AlphaComplex.from_points(ac.points)
    assert not fresh.has_signatures
    fresh.signatures()
    assert fresh.has_signatures
    fresh.save(tmp_path / "t.npz")
    monkeypatch.setattr(core.topology.betti, "build_topology",
                        lambda _: pytest.fail("saved topology was recomputed"))
    loaded = AlphaComplex.load(tmp_path / "t.npz")
    assert loaded.has_signatures
    last = float(fresh.spectrum()[-1])
    assert loaded.betti(alpha=last) == fresh.betti(alpha=last)
    np.testing.assert_array_equal(loaded.signatures().betti, fresh.signatures().betti)


@pytest.mark.parametrize("weighted", [False, True])
def test_the_last_value_is_the_spectrums_without_sorting(ac, weighted):
    """last_value (the opening alpha's cap, found without the spectrum's sort) is the
    spectrum's last value; weighted tables too, whose vertices enter at signed values."""
    rng = np.random.default_rng(ac.dim)
    if weighted:
        ac = AlphaComplex.from_points(ac.points, weights=rng.uniform(0.0, 0.02, len(ac.points)))
    fresh = TableIndex(ac.index.table, weighted=ac.index.weighted)
    assert fresh.last_value() == float(ac.spectrum()[-1])
    known = TableIndex(ac.index.table, weighted=ac.index.weighted,
                       known_spectrum=np.array([0.0, 1.5]))
    assert known.last_value() == 1.5


@pytest.mark.parametrize("gather_cost", [0, 10**12])  # always the gather; always the pass
def test_boundary_facets_by_either_path_are_the_definitions(ac, monkeypatch, gather_cost):
    """Both ways a shape finds its boundary facets (a pass over the facets that entered, or
    a gather of those not yet interior) give, at every alpha tried, the facets that entered
    and are not interior, split by their regular value (the table read plainly)."""
    import core.query.shape as shape_module

    monkeypatch.setattr(shape_module, "GATHER_COST", gather_cost)
    enter, regular, interior = (np.asarray(ac.index.intervals(ac.dim - 1))[:, k]
                                for k in range(3))
    spectrum = np.asarray(ac.spectrum())
    for alpha in spectrum[:: max(1, len(spectrum) // 40)]:
        shape = ac.shape(float(alpha))
        boundary = (enter <= alpha) & (interior > alpha)
        np.testing.assert_array_equal(shape.boundary_facets,
                                      np.asarray(ac.index.simplices(ac.dim - 1))[boundary])
        np.testing.assert_array_equal(shape.regular_facet_ids,
                                      np.flatnonzero(boundary & (regular <= alpha)))
        np.testing.assert_array_equal(shape.singular_ids(ac.dim - 1),
                                      np.flatnonzero(boundary & (regular > alpha)))

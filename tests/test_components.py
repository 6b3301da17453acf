"""core.topology.components: per-cell solid component labels agree with the signatures' component
count, join exactly the facet-adjacent cells, and come largest first."""

from __future__ import annotations

import numpy as np
import pytest

from core import AlphaComplex, InputError
from core.topology.components import facet_labels, solid_labels


@pytest.fixture(scope="module", params=[2, 3], ids=["2d", "3d"])
def complex_(request) -> AlphaComplex:
    """Three clusters of different sizes: several solid components over a range of alphas."""
    rng = np.random.default_rng(7)
    dim = request.param
    parts = [rng.normal(size=(n, dim)) * s + 6.0 * i
             for i, (n, s) in enumerate(((300, 1.0), (150, 0.6), (60, 0.3)))]
    return AlphaComplex.from_points(np.concatenate(parts))


def alphas(ac) -> np.ndarray:
    """A spread of spectrum alphas where the complex has cells."""
    spectrum = ac.spectrum()
    return spectrum[np.linspace(len(spectrum) // 10, len(spectrum) - 1, 12).astype(int)]


def test_labels_are_the_facet_connected_components(complex_) -> None:
    """Cells sharing a facet share a label; there are as many labels as solid components."""
    ac = complex_
    sig = ac.signatures()
    for alpha in alphas(ac):
        labels = solid_labels(ac, alpha)
        count = int(np.searchsorted(ac.intervals(ac.dim)[:, 0], alpha, side="right"))
        assert len(labels) == count
        assert len(np.unique(labels)) == sig.solid_components[sig.index(alpha)]
        sides = np.asarray(ac.facet_cells())
        inner = sides[((sides >= 0) & (sides < count)).all(axis=1)]
        np.testing.assert_array_equal(labels[inner[:, 0]], labels[inner[:, 1]])
        sizes = np.bincount(labels)
        assert np.all(np.diff(sizes) <= 0) and set(labels.tolist()) == set(range(len(sizes)))


def test_regular_facets_take_their_cells_label(complex_) -> None:
    """Each REGULAR facet gets the label of its one cell in the complex."""
    ac = complex_
    alpha = alphas(ac)[3]
    labels = solid_labels(ac, alpha)
    ids = ac.shape(alpha).regular_facet_ids
    got = facet_labels(ac, ids, labels)
    assert np.all(got >= 0)
    sides = np.asarray(ac.facet_cells())[ids]
    cell = np.where((sides[:, 0] >= 0) & (sides[:, 0] < len(labels)), sides[:, 0], sides[:, 1])
    np.testing.assert_array_equal(got, labels[cell])


def test_no_cells_and_bad_alpha(complex_) -> None:
    """At alpha 0 there are no cells; a negative alpha is an InputError."""
    assert len(solid_labels(complex_, 0.0)) == 0
    no_cells = np.zeros(0, dtype=np.int64)
    assert facet_labels(complex_, np.array([0, 1]), no_cells).tolist() == [-1, -1]
    with pytest.raises(InputError):
        solid_labels(complex_, -1.0)

"""Weighted tables against gudhi's weighted alpha complex (precision="exact"): simplices,
squared values, hidden points, Betti numbers and persistence pairs."""

from __future__ import annotations

import numpy as np
import pytest
from reference import SQ_RTOL
from weighted_reference import gudhi_betti, gudhi_weighted_table, ours_by_input_rows

from core import AlphaComplex
from core.geometry.power import signed_square


def uniform(rng: np.random.Generator, n: int, dim: int) -> np.ndarray:
    return rng.random((n, dim))


def clustered(rng: np.random.Generator, n: int, dim: int) -> np.ndarray:
    """Gaussian blobs of very different spreads."""
    centres = rng.random((4, dim)) * 10
    spread = np.array([0.03, 0.2, 1.0, 0.08])
    which = rng.integers(0, 4, n)
    return centres[which] + rng.normal(size=(n, dim)) * spread[which, None]


GENERATORS = {"uniform": uniform, "clustered": clustered}


def spacing_weights(rng: np.random.Generator, pts: np.ndarray, top: float) -> np.ndarray:
    """Weights from 0 to `top` times each point's squared nearest-neighbour distance."""
    from scipy.spatial import cKDTree

    dist, _ = cKDTree(pts).query(pts, k=2)
    return rng.uniform(0.0, top, len(pts)) * dist[:, 1] ** 2


def assert_matches_gudhi(ac, ref: dict, n_points: int) -> None:
    """Same vertices (so same hidden points), simplices and squared intervals as gudhi."""
    hidden = np.setdiff1d(np.arange(n_points), ref["vertices"])
    assert np.array_equal(np.flatnonzero(np.asarray(ac.input_index) < 0), hidden)
    for k in range(ref["dim"] + 1):
        rows, iv = ours_by_input_rows(ac, k)
        g_rows, *g_vals = ref[k]
        assert rows.shape == g_rows.shape, f"{k}-simplices: {len(rows)} ours, {len(g_rows)} gudhi"
        assert np.array_equal(rows, g_rows), f"{k}-simplices differ from gudhi's"
        for col, name in enumerate(("enter", "regular", "interior")):
            theirs = g_vals[col]
            assert np.array_equal(np.isinf(iv[:, col]), np.isinf(theirs)), f"{name}({k}) inf"
            fin = np.isfinite(theirs)
            np.testing.assert_allclose(iv[fin, col], theirs[fin], rtol=SQ_RTOL, atol=0,
                                       err_msg=f"{name} (squared) of {k}-simplices != gudhi")


def between_values(ref: dict) -> np.ndarray:
    """Squared values strictly between gudhi's critical values, and beyond both ends."""
    values = np.unique(np.concatenate([ref[k][1] for k in range(ref["dim"] + 1)]))
    mids = 0.5 * (values[1:] + values[:-1])
    return np.concatenate([[values[0] - 1.0], mids, [values[-1] + 1.0]])


@pytest.mark.parametrize("dim", [2, 3])
@pytest.mark.parametrize("kind", sorted(GENERATORS))
@pytest.mark.parametrize(("n", "top"), [(30, 0.3), (300, 1.0), (1500, 2.0)])
def test_weighted_table_equals_gudhi(kind: str, dim: int, n: int, top: float) -> None:
    rng = np.random.default_rng(100 * dim + n + len(kind))
    pts = GENERATORS[kind](rng, n, dim)
    w = spacing_weights(rng, pts, top)
    ac = AlphaComplex.from_points(pts, weights=w)
    ref = gudhi_weighted_table(pts, w)
    assert_matches_gudhi(ac, ref, n)
    shown = np.flatnonzero(ac.input_index >= 0)
    np.testing.assert_array_equal(ac.weights[ac.input_index[shown]], w[shown])


@pytest.mark.parametrize("dim", [2, 3])
def test_hidden_points_present_and_equal_gudhi(dim: int) -> None:
    rng = np.random.default_rng(40 + dim)
    pts = uniform(rng, 400, dim)
    w = spacing_weights(rng, pts, 4.0)  # heavy enough to hide many balls
    ac = AlphaComplex.from_points(pts, weights=w)
    n_hidden = int((ac.input_index < 0).sum())
    assert n_hidden > 20
    assert len(ac.points) == 400 - n_hidden
    assert_matches_gudhi(ac, gudhi_weighted_table(pts, w), 400)


@pytest.mark.parametrize("dim", [2, 3])
@pytest.mark.parametrize("kind", sorted(GENERATORS))
def test_betti_equal_gudhi_persistence_at_many_values(kind: str, dim: int) -> None:
    rng = np.random.default_rng(7 + dim + len(kind))
    pts = GENERATORS[kind](rng, 400, dim)
    w = spacing_weights(rng, pts, 2.0)
    ac = AlphaComplex.from_points(pts, weights=w)
    ref = gudhi_weighted_table(pts, w)
    at = between_values(ref)
    assert (at < 0).sum() > 50  # many negative squared values
    ours = np.array([ac.betti(alpha2=float(a)) for a in at])
    np.testing.assert_array_equal(ours, gudhi_betti(ref["st"], dim, at))


@pytest.mark.parametrize("dim", [2, 3])
def test_persistence_pairs_equal_gudhi(dim: int) -> None:
    rng = np.random.default_rng(70 + dim)
    pts = clustered(rng, 300, dim)
    w = spacing_weights(rng, pts, 1.5)
    ac = AlphaComplex.from_points(pts, weights=w)
    st = gudhi_weighted_table(pts, w)["st"]
    st.compute_persistence(min_persistence=0.0)
    for k in (0, dim - 1):
        ours = signed_square(np.asarray(ac.persistence().diagram(k)))
        theirs = np.asarray(st.persistence_intervals_in_dimension(k)).reshape(-1, 2)
        theirs = theirs[theirs[:, 1] > theirs[:, 0]]
        ours, theirs = (a[np.lexsort(a.T[::-1])] for a in (ours, theirs))
        assert ours.shape == theirs.shape
        np.testing.assert_allclose(ours, theirs, rtol=1e-9)


def test_signatures_betti_equal_gudhi_on_the_spectrum() -> None:
    rng = np.random.default_rng(12)
    pts = uniform(rng, 300, 3)
    w = spacing_weights(rng, pts, 1.0)
    ac = AlphaComplex.from_points(pts, weights=w)
    ref = gudhi_weighted_table(pts, w)
    sig = ac.signatures()
    sq = signed_square(np.asarray(sig.alphas))
    mids = np.append(0.5 * (sq[1:] + sq[:-1]), sq[-1] + 1.0)  # entry i holds up to alphas[i+1]
    np.testing.assert_array_equal(sig.betti, gudhi_betti(ref["st"], 3, mids))


@pytest.mark.parametrize("dim", [2, 3])
@pytest.mark.parametrize("values", [(0.0, 0.25), (0.0, 0.05, 0.2)])
def test_lattice_with_mixed_weights_has_gudhis_measure_and_components(dim: int, values) -> None:
    """Exact lattices with a few weight values are degenerate (co-orthospherical groups): the
    regular triangulation is not unique, so simplices may differ from gudhi's, as for classic
    lattices; the union of cells and the components must not."""
    from reference import simplex_measures

    axes = np.meshgrid(*[np.arange(5.0)] * dim, indexing="ij")
    pts = np.column_stack([a.ravel() for a in axes])
    w = np.random.default_rng(0).choice(values, len(pts))
    ac = AlphaComplex.from_points(pts, weights=w)
    ref = gudhi_weighted_table(pts, w)
    at = between_values(ref)
    cells, enter = ref[dim][0], ref[dim][1]
    theirs = [simplex_measures(pts, cells[enter <= a]).sum() for a in at]
    ours = [ac.shape(alpha2=float(a)).measure for a in at]
    np.testing.assert_allclose(ours, theirs, rtol=1e-12, atol=1e-12)
    components = [ac.betti(alpha2=float(a))[0] for a in at]
    np.testing.assert_array_equal(components, gudhi_betti(ref["st"], dim, at)[:, 0])


def test_planar_3d_weighted_input_equals_gudhi() -> None:
    rng = np.random.default_rng(5)
    u, v = rng.integers(0, 2**20, (2, 200)) / 2**20
    pts = np.column_stack([u, u - 2 * v + 1, v])  # dyadic: exactly on one tilted plane
    w = spacing_weights(rng, pts, 1.5)
    ac = AlphaComplex.from_points(pts, weights=w)
    assert (ac.dim, ac.ambient_dim) == (2, 3)
    ref = gudhi_weighted_table(pts, w)
    assert ref["dim"] == 2
    assert_matches_gudhi(ac, ref, len(pts))


@pytest.mark.parametrize("dim", [2, 3])
def test_values_near_zero_keep_their_relative_accuracy(dim: int) -> None:
    """Balls that barely overlap their nearest neighbour give edges whose power |c|² - w is
    a millionth of the terms subtracted: still equal to gudhi's exact values (rel. 1e-9)."""
    from scipy.spatial import cKDTree

    rng = np.random.default_rng(31 + dim)
    pts = uniform(rng, 2000, dim)
    dist, _ = cKDTree(pts).query(pts, k=2)
    w = dist[:, 1] ** 2 / 4 * (1 - 1e-6 * rng.choice([-1.0, 1.0], len(pts)))
    ac = AlphaComplex.from_points(pts, weights=w)
    ref = gudhi_weighted_table(pts, w)
    small = np.abs(ref[1][1]) < 1e-5 * np.median(np.abs(ref[1][1]))
    assert small.sum() > 50  # many edges with values near zero
    assert_matches_gudhi(ac, ref, len(pts))

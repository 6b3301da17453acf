"""The interval table against gudhi's alpha filtration on point sets in general position."""

from __future__ import annotations

import numpy as np
import pytest
from reference import (
    SQ_RTOL,
    assert_valid_table,
    gudhi_star_intervals,
    gudhi_table,
    ours_by_input_ids,
)

from core import AlphaComplex


def uniform(rng: np.random.Generator, n: int, dim: int) -> np.ndarray:
    """(n, dim) float64 uniform in the unit cube."""
    return rng.random((n, dim))


def clustered(rng: np.random.Generator, n: int, dim: int) -> np.ndarray:
    """(n, dim) float64 gaussian blobs of very different spreads, like a scan's dense patches."""
    centres = rng.random((5, dim)) * 10
    spread = np.array([0.02, 0.1, 0.5, 1.0, 0.05])
    which = rng.integers(0, 5, n)
    return centres[which] + rng.normal(size=(n, dim)) * spread[which, None]


GENERATORS = {"uniform": uniform, "clustered": clustered}


def assert_matches_gudhi(ac, ref: dict, rtol: float = SQ_RTOL) -> None:
    """Same simplices per dimension; enter**2, regular**2, interior**2 equal gudhi's within rtol."""
    assert ac.dim == ref["dim"]
    for k in range(ref["dim"] + 1):
        rows, iv = ours_by_input_ids(ac, k)
        g_rows, *g_vals = ref[k]
        assert rows.shape == g_rows.shape, f"{k}-simplices: {len(rows)} ours, {len(g_rows)} gudhi"
        assert np.array_equal(rows, g_rows), f"{k}-simplices differ from gudhi's"
        for col, name in enumerate(("enter", "regular", "interior")):
            ours, theirs = iv[:, col] ** 2, g_vals[col]
            assert np.array_equal(np.isinf(ours), np.isinf(theirs)), f"{name}({k}): inf differs"
            fin = np.isfinite(theirs)
            np.testing.assert_allclose(ours[fin], theirs[fin], rtol=rtol, atol=0,
                                       err_msg=f"{name}**2 of {k}-simplices != gudhi")


@pytest.mark.parametrize("dim", [2, 3])
@pytest.mark.parametrize("kind", sorted(GENERATORS))
@pytest.mark.parametrize("n", [20, 200, 2000])
def test_table_equals_gudhi(kind: str, dim: int, n: int) -> None:
    rng = np.random.default_rng(1000 * dim + n + len(kind))
    pts = GENERATORS[kind](rng, n, dim)
    ac = AlphaComplex.from_points(pts)
    assert len(ac.points) == n
    np.testing.assert_array_equal(np.asarray(ac.points)[ac.input_index], pts)
    assert_matches_gudhi(ac, gudhi_table(pts, precision="exact"))


@pytest.mark.parametrize("dim", [2, 3])
def test_table_equals_gudhi_on_shuffled_and_scaled_input(dim: int) -> None:
    rng = np.random.default_rng(7)
    pts = uniform(rng, 300, dim) * 1e-3 - 5e-4
    ac = AlphaComplex.from_points(pts[::-1].tolist())
    assert_matches_gudhi(ac, gudhi_table(pts[::-1]))


@pytest.mark.parametrize("dim", [2, 3])
def test_jittered_lattice_equals_gudhi_exact(dim: int) -> None:
    rng = np.random.default_rng(11)
    axes = np.meshgrid(*[np.arange(6.0)] * dim, indexing="ij")
    pts = np.column_stack([a.ravel() for a in axes]) + rng.uniform(-1e-3, 1e-3, (6**dim, dim))
    ac = AlphaComplex.from_points(pts)
    assert_valid_table(ac)
    assert_matches_gudhi(ac, gudhi_table(pts, precision="exact"))


def test_planar_3d_input_equals_gudhi() -> None:
    rng = np.random.default_rng(5)
    u, v = rng.integers(0, 2**20, (2, 150)) / 2**20
    pts = np.column_stack([u, u - 2 * v + 1, v])  # dyadic: exactly on one tilted plane
    ref = gudhi_table(pts)
    assert ref["dim"] == 2
    ac = AlphaComplex.from_points(pts)
    assert (ac.dim, ac.ambient_dim) == (2, 3)
    assert_matches_gudhi(ac, ref, rtol=1e-7)


@pytest.mark.parametrize("dim", [2, 3])
def test_reference_intervals_match_gudhi_cofaces(dim: int) -> None:
    """Reference self-check: vectorized regular/interior == gudhi's get_cofaces, one by one."""
    pts = uniform(np.random.default_rng(3), 25, dim)
    ref = gudhi_table(pts)
    for k in range(dim + 1):
        rows, _, reg, inter = ref[k]
        for row, r, i in zip(rows, reg, inter, strict=True):
            r_st, i_st = gudhi_star_intervals(ref["st"], [int(v) for v in row], dim)
            assert r == pytest.approx(r_st) and i == pytest.approx(i_st)


def test_table_valid_on_random_input() -> None:
    rng = np.random.default_rng(2)
    for dim in (2, 3):
        assert_valid_table(AlphaComplex.from_points(clustered(rng, 500, dim)))


# Found by hypothesis: triangle 0-2-3 is a needle (sides 6e-8, 55.6, 55.6).
NEEDLE = np.array([[0, 0, 0], [0, 0, 1], [0, 0.85, -55.5880345], [0, -5.96046448e-08, 0],
                   [1, 0, 0]])


@pytest.mark.parametrize("shift", range(len(NEEDLE)))
def test_needle_triangle_equals_gudhi_exact(shift: int) -> None:
    """A needle's circumradius must not come from |b - a|² = |a|² + |b|² - 2 a.b (it cancels to
    a negative square and a NaN radius); every input order puts another vertex first."""
    pts = np.roll(NEEDLE, shift, axis=0)
    ac = AlphaComplex.from_points(pts)
    assert_valid_table(ac)
    assert_matches_gudhi(ac, gudhi_table(pts, precision="exact"))

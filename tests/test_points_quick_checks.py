"""The quick paths of reading and checking points against their definitions: the spread
decided without an SVD (core.build.points.clearly_spread) and the median spacing from a quicker
tree give what the SVD and a brute-force nearest-neighbour search give."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.spatial import cKDTree
from scipy.spatial.distance import cdist

from core.build.points import Frame, check_spread, clearly_spread, flatness
from core.errors import InputError
from core.io.report import SPACING_SAMPLE, is_planar, median_spacing
from core.tolerances import FLAT_RTOL


def flat_by_svd(points: np.ndarray) -> bool:
    """The definition: the least singular value is within FLAT_RTOL of the largest."""
    s = flatness(points)[1]
    return bool(s[-1] <= FLAT_RTOL * s[0])


def thin_set(seed: int, n: int, dim: int, thickness: float, offset: float) -> np.ndarray:
    """n points spread in dim-1 directions of a random frame, `thickness` across the last,
    far from the origin by `offset` (rounding of the centre)."""
    rng = np.random.default_rng(seed)
    local = rng.uniform(-1.0, 1.0, (n, dim))
    local[:, -1] *= thickness
    basis, _ = np.linalg.qr(rng.normal(size=(dim, dim)))
    return local @ basis.T + offset


@settings(max_examples=60, deadline=None)
@given(seed=st.integers(0, 2**32 - 1), n=st.integers(4, 3000), dim=st.sampled_from([2, 3]),
       exponent=st.integers(-14, 0), offset=st.sampled_from([0.0, 1e3, 1e6]))
def test_clearly_spread_never_calls_a_flat_set_spread(seed, n, dim, exponent, offset):
    """Whenever the quick test says spread, the SVD says not flat; sets far from flat are
    decided quickly; check_spread and is_planar answer as the SVD alone does."""
    points = thin_set(seed, n, dim, 10.0 ** exponent, offset)
    flat = flat_by_svd(points)
    if clearly_spread(points):
        assert not flat
    if exponent >= -2:
        assert clearly_spread(points)
    assert outcome(check_spread, points) == outcome(spread_by_svd, points)
    if dim == 3:
        assert is_planar(points) == flat


def spread_by_svd(points: np.ndarray) -> Frame | None:
    """check_spread's definition on distinct points: the SVD alone decides."""
    centroid, s, vt = flatness(points)
    if s[0] == 0.0:
        raise InputError("all points are the same point")
    if s[1] <= FLAT_RTOL * s[0]:
        raise InputError("the points all lie on one line: an alpha shape needs 2D or 3D spread")
    if points.shape[1] == 3 and s[2] <= FLAT_RTOL * s[0]:
        return Frame(origin=centroid, basis=vt[:2].copy())
    return None


def outcome(check, points: np.ndarray) -> tuple:
    """What a spread check answers, comparably: its error message, or its frame's arrays."""
    try:
        frame = check(points)
    except InputError as error:
        return ("error", str(error))
    return ("frame", None) if frame is None else ("frame", frame.origin.tolist(),
                                                  frame.basis.tolist())


@pytest.mark.parametrize("points", [
    np.zeros((10, 3)),  # one point
    np.column_stack([np.arange(10.0), 2 * np.arange(10.0), np.zeros(10)]),  # a line
    np.column_stack([np.arange(10.0) % 3, np.arange(10.0) // 3, np.zeros(10)]),  # a plane
    np.column_stack([np.mgrid[0:4, 0:4].reshape(2, -1).T * 1e-300, np.zeros(16)]),  # tiny
])
def test_degenerate_sets_are_never_clearly_spread(points):
    assert not clearly_spread(points)


@pytest.mark.parametrize("n", [2, 700, SPACING_SAMPLE + 20_000])
def test_median_spacing_equals_the_nearest_neighbours_of_its_definition(n):
    """The quicker (unbalanced) tree finds the same nearest-neighbour distances: brute
    force for small sets, the default balanced tree on the same sample for big ones; ties
    (a grid) included."""
    rng = np.random.default_rng(n)
    for points in (rng.random((n, 3)), np.unique(rng.integers(0, 60, (n, 3)), axis=0) * 0.25):
        if len(points) <= 2000:
            distances = cdist(points, points)
            np.fill_diagonal(distances, np.inf)
            want = float(np.median(distances.min(axis=1)))
        else:
            sample = points if len(points) <= SPACING_SAMPLE else points[
                np.random.default_rng(0).choice(len(points), SPACING_SAMPLE, replace=False)]
            want = float(np.median(cKDTree(points).query(sample, k=2)[0][:, 1]))
        assert median_spacing(points) == want


def spatial_order_by_definition(points: np.ndarray) -> np.ndarray:
    """Morton order as it is defined, in one piece: whole-array codes with the grid's bits
    interleaved one by one (bit b of axis a at b * dim + a), numpy's stable sort."""
    dim = points.shape[1]
    bits = 32 if dim == 2 else 21
    low = points.min(axis=0)
    extent = float((points.max(axis=0) - low).max()) or 1.0
    grid = ((points - low) * ((2**bits - 1) / extent)).astype(np.uint64)
    code = np.zeros(len(points), dtype=np.uint64)
    for axis in range(dim):  # bits and axes, not points
        for b in range(bits):
            bit = (grid[:, axis] >> np.uint64(b)) & np.uint64(1)
            code |= bit << np.uint64(b * dim + axis)
    return np.argsort(code, kind="stable")


def canonical_order_by_definition(points: np.ndarray) -> np.ndarray:
    """Morton order as it is defined, in one piece: each coordinate as the 64-bit integer
    that orders as the float does (sign bit flipped for x >= 0, every bit for x < 0), all
    bits interleaved one by one (bit b of axis a at b * dim + a) into one Python integer,
    Python's stable sort."""
    dim = points.shape[1]
    bits = (points + 0.0).view(np.uint64)
    keys = [[~int(v) & (2**64 - 1) if int(v) >> 63 else int(v) | 2**63 for v in column]
            for column in bits.T.tolist()]
    codes = [0] * len(points)
    for axis in range(dim):
        for i, key in enumerate(keys[axis]):
            for b in range(64):
                if key >> b & 1:
                    codes[i] |= 1 << (b * dim + axis)
    return np.array(sorted(range(len(points)), key=codes.__getitem__), dtype=np.int64)


@pytest.mark.parametrize("dim", [2, 3])
@pytest.mark.parametrize("split", [False, True])
def test_canonical_order_in_chunks_is_its_definition(dim, split, monkeypatch):
    """Morton words made chunk by chunk, ties of the first word sorted by the later ones,
    give the very permutation of the one-piece definition (duplicates in input order)."""
    import core.build.points
    import core.parallel
    from core.build.points import canonical_order

    if split:
        monkeypatch.setattr(core.build.points, "CODE_CHUNK", 5)
        monkeypatch.setattr(core.parallel, "PARALLEL_ABOVE", 2)
    rng = np.random.default_rng(dim)
    for points in (rng.random((3001, dim)), rng.integers(0, 4, (2000, dim)) * 1.0,
                   np.concatenate([rng.random((500, dim)) * 1e-9, rng.random((3, dim)) * 1e6]),
                   rng.normal(size=(1500, dim)) * 1e-3 + 1.4e6, rng.normal(size=(900, dim)),
                   np.array([[0.0] * dim, [-0.0] * dim, [1.0] * dim])):
        np.testing.assert_array_equal(canonical_order(points),
                                      canonical_order_by_definition(points))


@pytest.mark.parametrize("dim", [2, 3])
@pytest.mark.parametrize("split", [False, True])
def test_spatial_order_in_chunks_and_halves_is_the_same_permutation(dim, split, monkeypatch):
    """Codes made chunk by chunk and sorted in two merged halves give the very permutation
    of the one-piece definition, ties (many points per grid cell, duplicates) in order."""
    import core.build.points
    import core.parallel
    from core.build.points import spatial_order
    from core.parallel import argsort_stable

    if split:
        monkeypatch.setattr(core.build.points, "CODE_CHUNK", 5)
        monkeypatch.setattr(core.parallel, "PARALLEL_ABOVE", 2)
    rng = np.random.default_rng(dim)
    for points in (rng.random((3001, dim)), rng.integers(0, 4, (2000, dim)) * 1.0,
                   np.concatenate([rng.random((500, dim)) * 1e-9, rng.random((3, dim)) * 1e6])):
        np.testing.assert_array_equal(spatial_order(points), spatial_order_by_definition(points))
    for values in (rng.integers(0, 7, 1001), rng.random(1000), np.zeros(10, np.uint64)):
        np.testing.assert_array_equal(argsort_stable(values), np.argsort(values, kind="stable"))

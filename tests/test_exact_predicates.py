"""core.geometry.predicates / core.geometry.exact against Fractions on adversarial
(near-degenerate) inputs."""

from __future__ import annotations

from fractions import Fraction

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from core.geometry.exact import exact_ints, exact_radii
from core.geometry.predicates import diametral_signs, in_sphere, orientations

SETTINGS = settings(max_examples=60, deadline=None)


def _sign(x: Fraction) -> int:
    return (x > 0) - (x < 0)


def _det(m: list[list[Fraction]]) -> Fraction:
    if len(m) == 1:
        return m[0][0]
    return sum(((-1) ** j * m[0][j] * _det([r[:j] + r[j + 1:] for r in m[1:]])
                for j in range(len(m))), Fraction(0))


def _exact(p: np.ndarray) -> list[Fraction]:
    return [Fraction(float(x)) for x in p]


def _centre(corners: list[list[Fraction]]) -> list[Fraction]:
    """Circumcentre of a full-dimensional simplex by Cramer's rule."""
    d = len(corners[0])
    a = [[2 * (c[k] - corners[0][k]) for k in range(d)] for c in corners[1:]]
    b = [sum(c[k] ** 2 - corners[0][k] ** 2 for k in range(d)) for c in corners[1:]]
    det = _det(a)
    return [_det([[*row[:k], b[i], *row[k + 1:]] for i, row in enumerate(a)]) / det
            for k in range(d)]


@st.composite
def near_degenerate(draw, dim: int):
    """A small lattice (cospherical, coplanar groups) moved by 0 or a few ulps to 1e-9, far
    from the origin or not: the inputs where float predicates go wrong."""
    rng = np.random.default_rng(draw(st.integers(0, 2**32 - 1)))
    axes = np.meshgrid(*[np.arange(3.0)] * dim, indexing="ij")
    pts = np.column_stack([a.ravel() for a in axes])
    noise = draw(st.sampled_from([0.0, 1e-15, 1e-13, 1e-11, 1e-9]))
    pts = pts + rng.normal(size=pts.shape) * noise
    return pts * draw(st.sampled_from([1.0, 0.1, 3e-7])) + draw(st.sampled_from([0.0, 1e3]))


def _rows(pts: np.ndarray, width: int, seed: int, n: int = 40) -> np.ndarray:
    rng = np.random.default_rng(seed)
    return np.array([rng.choice(len(pts), width, replace=False) for _ in range(n)])


@SETTINGS
@given(st.sampled_from([2, 3]).flatmap(lambda d: near_degenerate(d)), st.integers(0, 99))
def test_orientation_signs_are_exact(pts: np.ndarray, seed: int) -> None:
    d = pts.shape[1]
    rows = _rows(pts, d + 1, seed)
    signs, _ = orientations(pts, rows)
    for row, got in zip(rows, signs, strict=True):
        corners = [_exact(pts[i]) for i in row]
        want = _sign(_det([[a - b for a, b in zip(c, corners[0], strict=True)]
                           for c in corners[1:]]))
        assert got == want


@SETTINGS
@given(st.sampled_from([2, 3]).flatmap(lambda d: near_degenerate(d)), st.integers(0, 99))
def test_in_sphere_is_exact_off_the_sphere(pts: np.ndarray, seed: int) -> None:
    d = pts.shape[1]
    rows = _rows(pts, d + 2, seed)
    cells, queries = rows[:, :-1], rows[:, -1]
    signs, _ = orientations(pts, cells)
    solid = signs != 0
    inside, _ = in_sphere(pts, cells[solid], queries[solid], signs[solid],
                          np.linspace(0.1, 0.9, len(pts)))
    for cell, q, got in zip(cells[solid], queries[solid], inside, strict=True):
        corners = [_exact(pts[i]) for i in cell]
        c = _centre(corners)
        r2 = sum((a - b) ** 2 for a, b in zip(corners[0], c, strict=True))
        q2 = sum((a - b) ** 2 for a, b in zip(_exact(pts[q]), c, strict=True))
        if q2 != r2:  # on the sphere: the perturbation decides (tested below)
            assert got == (q2 < r2)


@SETTINGS
@given(st.sampled_from([2, 3]).flatmap(lambda d: near_degenerate(d)), st.integers(0, 99))
def test_diametral_signs_are_exact(pts: np.ndarray, seed: int) -> None:
    d = pts.shape[1]
    for width in range(2, d + 1):
        rows = _rows(pts, width + 1, seed)
        simplices, queries = rows[:, :-1], rows[:, -1]
        signs, _ = diametral_signs(pts, simplices, queries)
        for simplex, q, got in zip(simplices, queries, signs, strict=True):
            corners = [np.array(_exact(pts[i]), dtype=object) for i in simplex]
            qq = np.array(_exact(pts[q]), dtype=object)
            if width == 2:
                want = _sign(np.dot(corners[0] - qq, corners[1] - qq))
            else:
                u, v, w = corners[1] - corners[0], corners[2] - corners[0], qq - corners[0]
                n = np.cross(u, v)
                if np.dot(n, n) == 0:
                    continue
                o = (np.dot(u, u) * np.cross(v, n) + np.dot(v, v) * np.cross(n, u)) / (
                    2 * np.dot(n, n))
                want = _sign(np.dot(w - o, w - o) - np.dot(o, o))
            assert got == want


def test_perturbation_is_consistent_on_a_circle() -> None:
    """12 exactly cocircular points: for every quadrilateral a, c, b, d, the edge ab is
    Delaunay from both sides alike, and exactly one of its two diagonals is."""
    pts = np.array([[5, 0], [0, 5], [-5, 0], [0, -5], [3, 4], [4, 3], [-3, 4], [-4, 3],
                    [3, -4], [4, -3], [-3, -4], [-4, -3]], dtype=float)
    angle = np.arctan2(pts[:, 1], pts[:, 0])
    ties = np.random.default_rng(3).random(len(pts))
    rng = np.random.default_rng(0)
    for _ in range(50):
        a, c, b, d = sorted(rng.choice(len(pts), 4, replace=False), key=lambda i: angle[i])

        def inside(tri: list[int], q: int) -> bool:
            rows = np.array([tri])
            sign, _ = orientations(pts, rows)
            return bool(in_sphere(pts, rows, np.array([q]), sign, ties)[0][0])
        assert inside([a, b, c], d) == inside([b, a, d], c)
        assert inside([a, b, c], d) != inside([c, d, a], b)


@SETTINGS
@given(near_degenerate(3), st.integers(0, 99))
def test_exact_integers_and_radii(pts: np.ndarray, seed: int) -> None:
    ints = exact_ints(pts)
    k = int(np.flatnonzero(pts.ravel())[0])
    ratio = Fraction(float(pts.ravel()[k])) / Fraction(int(ints.ravel()[k]))
    for x, i in zip(pts.ravel(), ints.ravel(), strict=True):
        assert Fraction(float(x)) == ratio * int(i) or x == 0
    rows = _rows(pts, 4, seed, n=10)
    signs, _ = orientations(pts, rows)
    rows = rows[signs != 0]
    for row, got in zip(rows, exact_radii(pts, rows), strict=True):
        corners = [_exact(pts[i]) for i in row]
        c = _centre(corners)
        want = float(sum((a - b) ** 2 for a, b in zip(corners[0], c, strict=True)))
        assert got * got == np.float64(want) or abs(got * got - want) <= 4e-16 * want


def test_exact_zeros_take_the_exact_path() -> None:
    """Coplanar lattice rows: the float filter cannot prove a sign; exact says 0."""
    pts = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 0], [0.1, 0.3, 0.0]]) + 1e3
    rows = np.array([[0, 1, 2, 3], [0, 1, 2, 4], [1, 2, 3, 4]])
    signs, n_exact = orientations(pts, rows)
    assert signs.tolist() == [0, 0, 0] and n_exact == 3

"""Closed forms of 2-, 3- and 4-ball intersections against analytic values, quadrature and
Monte Carlo (each term checked on its own)."""

from __future__ import annotations

import numpy as np
import pytest
import shapely
from scipy import integrate

from core.molecule.intersections import four_balls, radical_point, three_balls, two_balls


def lens_volume(d, r1, r2):
    """The textbook lens volume of two overlapping balls."""
    return (np.pi * (r1 + r2 - d) ** 2 * (d * d + 2 * d * (r1 + r2) - 3 * (r1 - r2) ** 2)
            / (12 * d))


@pytest.mark.parametrize(("d", "r1", "r2"), [(1.0, 1.0, 1.0), (1.5, 1.0, 2.0), (0.3, 1.2, 1.0),
                                             (2.9, 1.5, 1.5)])
def test_two_balls_exact(d, r1, r2):
    c = np.array([[[0.0, 0, 0], [d, 0, 0]]])
    volume, caps = two_balls(c, np.array([[r1, r2]]))
    assert volume[0] == pytest.approx(lens_volume(d, r1, r2), rel=1e-13)
    h1 = r1 - (d * d + r1 * r1 - r2 * r2) / (2 * d)
    assert caps[0, 0] == pytest.approx(2 * np.pi * r1 * h1, rel=1e-13)


def sliced_volume(c, r):
    """vol of three balls' intersection: slices parallel to the centres' plane, each the
    intersection of three disks as shapely polygons of 2^15 sides, integrated by quad."""
    n = np.cross(c[1] - c[0], c[2] - c[0])
    n /= np.linalg.norm(n)
    e1 = (c[1] - c[0]) / np.linalg.norm(c[1] - c[0])
    e2 = np.cross(n, e1)
    flat = (c - c[0]) @ np.stack([e1, e2]).T
    _, t = radical_point(c[None], r[None])

    def area(z):
        disks = [shapely.Point(*p).buffer(np.sqrt(max(ri * ri - z * z, 0.0)), quad_segs=8192)
                 for p, ri in zip(flat, r, strict=True)]
        return shapely.intersection_all(disks).area

    return 2 * integrate.quad(area, 0.0, float(r.min()), points=[float(t[0])], epsabs=1e-12,
                              epsrel=1e-10)[0]


def test_three_balls_against_quadrature():
    c = np.array([[0.0, 0, 0], [1.2, 0.1, 0.2], [0.4, 1.0, -0.3]])
    r = np.array([1.0, 1.1, 0.9])
    volume, _ = three_balls(c[None], r[None])
    assert volume[0] == pytest.approx(sliced_volume(c, r), rel=1e-6)


def test_three_equal_balls_symmetric():
    """Three unit balls on a small equilateral triangle: each sphere's share is a third."""
    c = 0.3 * np.array([[1.0, 0, 0], [-0.5, np.sqrt(3) / 2, 0], [-0.5, -np.sqrt(3) / 2, 0]])
    volume, areas = three_balls(c[None], np.ones((1, 3)))
    assert np.ptp(areas) < 1e-12
    assert volume[0] == pytest.approx(sliced_volume(c, np.ones(3)), rel=1e-6)


def monte_carlo(c, r, rng, n=2_000_000):
    """(volume, its standard error, sphere areas, their standard errors) by sampling."""
    lo, hi = (c - r[:, None]).max(0), (c + r[:, None]).min(0)
    x = rng.uniform(lo, hi, size=(n, 3))
    frac = np.all(((x[:, None] - c) ** 2).sum(-1) <= r ** 2, axis=1).mean()
    box = np.prod(hi - lo)
    areas, errors = [], []
    for i in range(len(c)):
        y = rng.normal(size=(n // 2, 3))
        y = c[i] + r[i] * y / np.linalg.norm(y, axis=1)[:, None]
        others = np.arange(len(c)) != i
        p = np.all(((y[:, None] - c[others]) ** 2).sum(-1) <= r[others] ** 2, axis=1).mean()
        full = 4 * np.pi * r[i] ** 2
        areas.append(p * full)
        errors.append(full * np.sqrt(p * (1 - p) / (n // 2)))
    return frac * box, box * np.sqrt(frac * (1 - frac) / n), np.array(areas), np.array(errors)


@pytest.mark.parametrize("k", [3, 4])
def test_balls_against_monte_carlo(k):
    rng = np.random.default_rng(k)
    checked = 0
    while checked < 3:
        c, r = rng.normal(size=(k, 3)), rng.uniform(1.0, 2.0, size=k)
        z, _ = radical_point(c[None], r[None])
        if ((z[0] - c[0]) ** 2).sum() > r[0] ** 2:  # not a dual-complex simplex
            continue
        volume, areas = (three_balls if k == 3 else four_balls)(c[None], r[None])
        mc_volume, mc_err, mc_areas, mc_area_err = monte_carlo(c, r, rng)
        assert abs(volume[0] - mc_volume) < 5 * mc_err + 1e-12
        assert np.all(np.abs(areas[0] - mc_areas) < 5 * mc_area_err + 1e-12)
        checked += 1

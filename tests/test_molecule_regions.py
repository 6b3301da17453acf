"""Exact measures of voids and pockets against independent sampling: the sector pieces of a
tetrahedron's balls, a hollow shell's cavity (>= 10^7 Monte Carlo samples), a cup's pocket
and its one mouth, and the sums with the union's exact area."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.spatial import cKDTree

from core.complex import AlphaComplex
from core.molecule.cavities import void_cells
from core.molecule.flow import barycentric_orthocentres
from core.molecule.measures import union_measures
from core.molecule.pockets import find_pockets, open_area
from core.molecule.regions import dual_facts, region_measures
from core.molecule.sectors import tet_pieces, tet_volumes
from tests.molecule_reference import free_in_tets, shell, uniform_in_tets

TET = 10.0 * np.array([[0.0, 0, 0], [1, 0, 0], [0.5, np.sqrt(3) / 2, 0],
                       [0.5, np.sqrt(3) / 6, np.sqrt(2 / 3)]])


def _in_tet(x: np.ndarray, corners: np.ndarray) -> np.ndarray:
    """(p,) bool: points x (p, 3) inside the tetrahedron corners (4, 3)."""
    lam = np.linalg.solve((corners[1:] - corners[0]).T, (x - corners[0]).T).T
    return (lam >= 0).all(1) & (lam.sum(1) <= 1)


def _sphere_points(centres, radii, per_area: float, rng):
    """Uniform points on every sphere, about per_area per Å²: (points, ball, weight Å²)."""
    counts = np.maximum((per_area * 4 * np.pi * radii ** 2).astype(int), 1)
    ball = np.repeat(np.arange(len(radii)), counts)
    u = rng.normal(size=(len(ball), 3))
    u /= np.linalg.norm(u, axis=1, keepdims=True)
    weight = (4 * np.pi * radii ** 2 / counts)[ball]
    return centres[ball] + radii[ball, None] * u, ball, weight


def _sampled_area(hit: np.ndarray, ball: np.ndarray, weight: np.ndarray
                  ) -> tuple[float, float]:
    """(area, standard error) of the sphere points `hit` (per-sphere binomial errors)."""
    count = np.bincount(ball)
    q = np.bincount(ball, weights=hit, minlength=len(count)) / np.maximum(count, 1)
    w = np.bincount(ball, weights=weight, minlength=len(count)) / np.maximum(count, 1)
    return float((weight * hit).sum()), float(np.sqrt((w ** 2 * count * q * (1 - q)).sum()))


def _exposed(x, ball, centres, radii, k: int = 24) -> np.ndarray:
    """(p,) bool: sphere points of `ball` outside every other ball (the k nearest centres
    within the largest radius decide; the test balls are sparse enough)."""
    dist, idx = cKDTree(centres).query(x, k=min(k, len(radii)),
                                       distance_upper_bound=radii.max())
    found = np.isfinite(dist)
    near = np.where(found, idx, 0)
    return ~(found & (near != ball[:, None]) & (dist < radii[near])).any(1)


@pytest.mark.parametrize(("radii", "edges", "faces"), [
    ((2.0, 2.5, 3.0, 2.0), (), ()),  # four apart: four ball sectors
    ((6.0, 5.0, 2.0, 2.0), (0,), ()),  # two balls meet: a lens wedge
    ((6.0, 6.0, 6.0, 2.0), (0, 1, 3), (3,)),  # three meet: half their common body
])
def test_tetrahedron_pieces_against_sampling(radii, edges, faces):
    """Volume of the balls inside one tetrahedron and each sphere's exposed area inside it,
    against 2·10^6 uniform samples of the tetrahedron and of the spheres."""
    rng = np.random.default_rng(1)
    r = np.array(radii)
    edge_in, face_in = np.zeros((1, 6), bool), np.zeros((1, 4), bool)
    edge_in[0, list(edges)], face_in[0, list(faces)] = True, True
    covered, area = tet_pieces(TET[None], r[None], edge_in, face_in)
    n = 2_000_000
    x, _ = uniform_in_tets(TET[None], n, rng)
    inside = (np.linalg.norm(x[:, None] - TET[None], axis=2) <= r).any(1)
    vol = tet_volumes(TET[None])[0]
    p = inside.mean()
    error = vol * np.sqrt(p * (1 - p) / n)  # standard error, about 0.04 Å³
    assert abs(covered[0] - p * vol) < 4 * error
    pts, ball, _ = _sphere_points(TET, r, 400, rng)
    keep = _in_tet(pts, TET)
    exposed = keep.copy()
    exposed[keep] = _exposed(pts[keep], ball[keep], TET, r)
    count = np.bincount(ball, minlength=4)
    q = np.bincount(ball, weights=exposed, minlength=4) / count
    sphere = 4 * np.pi * r ** 2
    error = sphere * np.sqrt(q * (1 - q) / count)  # binomial standard error per sphere
    assert np.all(np.abs(area[0] - q * sphere) < 4 * error)


def _closed_shell(probe: float, seed: int = 3) -> tuple[np.ndarray, np.ndarray]:
    """260 balls of radius 1 + probe on a sphere of radius 5, centres jittered 0.05 Å."""
    centres, radii = shell((0.0, 0, 0), 5.0, 260, 1.0 + probe)
    return centres + np.random.default_rng(seed).normal(0, 0.05, centres.shape), radii


def _cavity(centres, radii):
    facts = dual_facts(AlphaComplex.from_points(centres, weights=radii ** 2))
    labels = void_cells(~facts.cell_in, facts.facet_cells, ~facts.facet_in)
    return facts, labels, region_measures(facts, labels, int(labels.max()) + 1)


@pytest.mark.parametrize("probe", [0.0, 0.4])
def test_hollow_shell_cavity_volume_against_1e7_samples(probe):
    """A closed shell of equal balls: its one cavity's exact volume against 10^7 uniform
    samples of the cube [-5, 5]³ (empty and within 5 Å of the centre: the shell's balls
    close the sphere of radius 5, checked on the samples near it)."""
    centres, radii = _closed_shell(probe)
    _, labels, voids = _cavity(centres, radii)
    assert labels.max() == 0
    tree, rng, n, empty, band = cKDTree(centres), np.random.default_rng(0), 10_000_000, 0, 0
    deep = 5.0 - 0.25 - radii[0]  # no ball reaches within this radius (jitter <= 0.25 Å)
    assert np.linalg.norm(centres, axis=1).min() - radii[0] > deep
    for _ in range(10):
        x = rng.uniform(-5, 5, size=(n // 10, 3))
        rho = np.linalg.norm(x, axis=1)
        ask = (rho > deep) & (rho < 5.1)
        free = rho <= deep
        free[ask] = tree.query(x[ask])[0] > radii[0]  # equal radii: the nearest centre decides
        empty += int((free & (rho < 5)).sum())
        band += int((free & (np.abs(rho - 5) < 0.1)).sum())
    assert band == 0  # no empty sample on the shell's sphere: the cavity is all of it inside
    p = empty / n
    volume, error = 1000 * p, 1000 * np.sqrt(p * (1 - p) / n)  # error about 0.14 Å³
    assert abs(voids.volume[0] - volume) < 4 * error


@pytest.mark.parametrize("probe", [0.0, 0.4])
def test_hollow_shell_lining_area_and_outer_area(probe):
    """The cavity's lining area against sampled exposed sphere points inside radius 5, and
    the union's exact total area less the lining against the sampled outer area."""
    centres, radii = _closed_shell(probe)
    _, _, voids = _cavity(centres, radii)
    ac = AlphaComplex.from_points(centres, weights=radii ** 2)
    simplices = [ac.simplices(d)[ac.intervals_sq(d)[:, 0] <= 0] for d in range(4)]
    total = union_measures(ac.points, np.sqrt(ac.weights), *simplices[1:],
                           vertices=simplices[0][:, 0]).area
    rng = np.random.default_rng(5)
    pts, ball, weight = _sphere_points(centres, radii, 150, rng)
    exposed = _exposed(pts, ball, centres, radii)
    inner = np.linalg.norm(pts, axis=1) < 5
    sampled, error = _sampled_area(exposed & inner, ball, weight)  # error about 0.6 Å²
    assert abs(voids.area[0] - sampled) < 4 * error
    sampled, error = _sampled_area(exposed & ~inner, ball, weight)
    assert abs(total - voids.area[0] - sampled) < 4 * error


def _cup(seed: int = 4, radius: float = 1.2, spread: float = 0.0
         ) -> tuple[np.ndarray, np.ndarray]:
    """A hollow shell with its top cap (z > 3 Å) removed: a cup with one opening. Radii
    `radius`, each scaled by a uniform factor in 1 ± spread."""
    centres, radii = shell((0.0, 0, 0), 5.0, 300, radius)
    rng = np.random.default_rng(seed)
    centres = centres + rng.normal(0, 0.05, centres.shape)
    radii = radii * rng.uniform(1 - spread, 1 + spread, len(radii))
    keep = centres[:, 2] < 3.0
    return centres[keep], radii[keep]


def test_cup_has_one_pocket_with_one_mouth_at_its_rim():
    centres, radii = _cup()
    ac = AlphaComplex.from_points(centres, weights=radii ** 2)
    facts = dual_facts(ac)
    pockets = find_pockets(facts)
    assert len(pockets) >= 1
    big = 0
    assert pockets.volume[big] > 50 * pockets.volume[1:].sum(initial=0.0) / max(len(pockets), 1)
    assert len(pockets.mouths(big)) == 1
    mouth = pockets.facets[pockets.facet_mouth == pockets.mouths(big)[0]]
    rim_z = facts.centres[facts.triangles[mouth]][..., 2]
    assert rim_z.min() > 1.5  # the mouth spans the opening, near the cut at z = 3
    # the pocket fills the cup: most of the empty space inside the sphere of radius 3.8
    assert pockets.volume[big] > 0.8 * 4 / 3 * np.pi * 3.8 ** 3 / 2
    assert pockets.mouth_area[pockets.mouths(big)[0]] > 0


@pytest.mark.parametrize(("radius", "spread"), [(1.2, 0.0), (2.0, 0.0), (1.6, 0.2)])
def test_cup_pocket_volume_and_area_exact_against_1e7_samples(radius, spread):
    """The cup's pocket: its exact volume against 10^7 uniform samples of its tetrahedra
    (empty: in no ball; standard error about 0.07 Å³) and its lining area against points on
    every sphere (100 per Å², exposed and inside its tetrahedra), both within 4 standard
    errors. The balls reach through the mouth's triangles (radius 2.0) and some balls are
    vertices of the triangulation but not of K (spread radii)."""
    from core.query.locate import Locator

    centres, radii = _cup(radius=radius, spread=spread)
    ac = AlphaComplex.from_points(centres, weights=radii ** 2)
    facts = dual_facts(ac)
    pockets = find_pockets(facts)
    mine = facts.cells[pockets.cells == 0]
    rng = np.random.default_rng(2)
    volume, error = free_in_tets(facts.centres[mine], facts.centres, facts.radii,
                                  10_000_000, rng)
    assert abs(pockets.volume[0] - volume) < 4 * error
    pts, ball, weight = _sphere_points(facts.centres, facts.radii, 100, rng)
    locator = Locator(facts.centres, facts.cells, ac.face_ids(3), facts.facet_cells)
    cell = locator.locate(pts)  # -1 outside the hull
    inside = (cell >= 0) & (pockets.cells[np.maximum(cell, 0)] == 0)
    exposed = inside.copy()
    exposed[inside] = _exposed(pts[inside], ball[inside], facts.centres, facts.radii)
    sampled, error = _sampled_area(exposed, ball, weight)
    assert abs(pockets.area[0] - sampled) < 4 * error


def test_orthocentre_has_equal_power_and_open_area_of_a_bare_triangle():
    centres, radii = _cup()
    facts = dual_facts(AlphaComplex.from_points(centres, weights=radii ** 2))
    lam = barycentric_orthocentres(facts)[:50]
    z = np.einsum("ti,tij->tj", lam, facts.centres[facts.cells[:50]])
    power = ((z[:, None] - facts.centres[facts.cells[:50]]) ** 2).sum(2) \
        - facts.radii[facts.cells[:50]] ** 2
    assert np.allclose(power, power[:, :1], atol=1e-8)
    bare = np.flatnonzero(~facts.edge_in[facts.tri_edges].any(1))
    c = facts.centres[facts.triangles[bare]]
    double = np.linalg.norm(np.cross(c[:, 1] - c[:, 0], c[:, 2] - c[:, 0]), axis=1)
    heights = double[:, None] / np.linalg.norm(c[:, [1, 2, 0]] - c[:, [2, 0, 1]], axis=2)
    bare, double = bare[(heights > radii[0]).all(1)], double[(heights > radii[0]).all(1)]
    assert len(bare)
    # disks apart, none reaching its opposite edge: the triangle less half a disk (the
    # corner angles sum to pi)
    assert np.allclose(open_area(facts, bare), double / 2 - np.pi * radii[0] ** 2 / 2)


def test_flat_cell_has_its_centroid_for_orthocentre():
    """A cell without volume (four coplanar centres) neither fails nor flows anywhere."""
    from core.molecule.regions import DualFacts

    centres = np.array([[0.0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 0], [0, 0, 1], [1, 0, 1],
                        [0, 1, 1], [0.5, 0.5, 2]])
    cells = np.array([[0, 1, 2, 3], [0, 1, 2, 4]])
    none = np.zeros(0, np.int64)
    facts = DualFacts(centres, np.ones(8), cells, np.zeros(2, bool), none, none, none, none,
                      none, none, none)
    lam = barycentric_orthocentres(facts)
    assert np.allclose(lam[0], 0.25) and np.isclose(lam[1].sum(), 1.0)

"""Union of balls: exact area against freesasa, volume against Monte Carlo, cavities against
gudhi's b2 and a voxel flood-fill (all computed from gudhi's dual complex)."""

from __future__ import annotations

import freesasa  # noqa: F401  (required: the reference libraries fail the run when missing)
import gudhi  # noqa: F401
import numpy as np
import pytest

from core.complex import AlphaComplex
from core.molecule.cavities import void_cells
from core.molecule.measures import dual_simplices, exposed_balls, union_measures
from core.molecule.regions import dual_facts, region_measures
from tests.molecule_reference import (
    dual_at_zero,
    facet_cells,
    flood_fill_voids,
    freesasa_area,
    gudhi_betti2,
    gudhi_dual,
    monte_carlo_volume,
    shell,
)


def measures(centres, radii):
    k = dual_at_zero(gudhi_dual(centres, radii))
    return union_measures(centres, radii, k[1], k[2], k[3], vertices=k[0][:, 0])


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_random_balls_area_matches_freesasa(seed):
    rng = np.random.default_rng(seed)
    n = 200
    centres, radii = rng.uniform(0, 9, size=(n, 3)), rng.uniform(0.8, 2.2, size=n)
    m = measures(centres, radii)
    total, per_atom = freesasa_area(centres, radii)
    assert m.area == pytest.approx(total, rel=1e-3)
    assert np.abs(m.atom_area - per_atom).max() < 2e-3 * per_atom.max()
    volume, err = monte_carlo_volume(centres, radii, rng)
    assert abs(m.volume - volume) < 5 * err


def test_measures_do_not_depend_on_the_batch_size(monkeypatch):
    """The simplices are measured in batches (cache-sized): area, volume and every atom's
    area are the same, to the last bit, whatever the batch size."""
    import core.molecule.measures as measures_module

    rng = np.random.default_rng(7)
    centres, radii = rng.uniform(0, 12, size=(400, 3)), rng.uniform(0.8, 2.2, size=400)
    k = dual_at_zero(gudhi_dual(centres, radii))
    results = []
    for chunk in (7, 100, 1 << 13):
        monkeypatch.setattr(measures_module, "CHUNK", chunk)
        results.append(union_measures(centres, radii, k[1], k[2], k[3], vertices=k[0][:, 0]))
    for other in results[1:]:
        assert (other.area, other.volume) == (results[0].area, results[0].volume)
        assert np.array_equal(other.atom_area, results[0].atom_area)


def sphere_samples(n: int) -> np.ndarray:
    """(n, 3) unit vectors spread evenly over the sphere (a Fibonacci lattice)."""
    k = np.arange(n) + 0.5
    z = 1 - 2 * k / n
    phi = np.pi * (1 + 5 ** 0.5) * k
    rho = np.sqrt(1 - z ** 2)
    return np.column_stack([rho * np.cos(phi), rho * np.sin(phi), z])


def test_exposed_balls_against_samples_of_each_sphere():
    """A ball is exposed when a point of its sphere lies outside every other ball: each
    sphere sampled at 2,000 points. No sampled exposure is missed; every ball left out has no
    exposed sample, and every ball kept with more than 1% of its sphere exposed has some."""
    from scipy.spatial import cKDTree

    rng = np.random.default_rng(0)
    n = 400
    centres, radii = rng.uniform(0, 8, size=(n, 3)), rng.uniform(0.8, 2.2, size=n)
    exposed = exposed_balls(measures(centres, radii).atom_area, radii)
    unit = sphere_samples(2000)
    tree = cKDTree(centres)
    sampled = np.zeros(n, bool)
    for i in range(n):
        x = centres[i] + radii[i] * unit
        near = [j for j in tree.query_ball_point(centres[i], radii[i] + radii.max()) if j != i]
        d = np.linalg.norm(x[:, None, :] - centres[near][None], axis=2)
        sampled[i] = bool((d > radii[near][None] * (1 + 1e-9)).all(axis=1).any())
    assert 0 < (~exposed).sum() < n  # buried balls and exposed ones
    assert (exposed | ~sampled).all()  # never left out where a sample is exposed
    big = measures(centres, radii).atom_area > 0.01 * 4 * np.pi * radii ** 2
    assert (sampled | ~big).all()


def test_nested_ball_counts_nothing():
    """A ball inside another adds no area and no volume (it leaves the dual complex)."""
    centres = np.array([[0.0, 0, 0], [0.3, 0, 0], [2.5, 0, 0], [1.0, 1.8, 0.2]])
    radii = np.array([2.0, 0.5, 1.0, 1.0])
    m = measures(centres, radii)
    total, _ = freesasa_area(centres, radii)
    assert m.atom_area[1] == 0
    assert m.area == pytest.approx(total, rel=1e-3)


def test_two_and_three_balls_union_exact():
    """Union volume of 2 balls from the lens formula; 3 balls from inclusion-exclusion."""
    centres = np.array([[0.0, 0, 0], [1.5, 0, 0]])
    radii = np.array([1.0, 1.2])
    d, r1, r2 = 1.5, 1.0, 1.2
    lens = (np.pi * (r1 + r2 - d) ** 2 * (d * d + 2 * d * (r1 + r2) - 3 * (r1 - r2) ** 2)
            / (12 * d))
    m = measures(centres, radii)
    assert m.volume == pytest.approx(4 / 3 * np.pi * (r1 ** 3 + r2 ** 3) - lens, rel=1e-12)


@pytest.mark.parametrize("shells", [1, 2])
def test_hollow_shells_have_one_cavity_each(shells):
    parts = [shell((12.0 * s, 0, 0), 5.0, 260, 1.0) for s in range(shells)]
    centres = np.concatenate([p[0] for p in parts])
    radii = np.concatenate([p[1] for p in parts])
    table = gudhi_dual(centres, radii)
    tets, tet_enter = table[3]
    tris, tri_enter = table[2]
    labels = void_cells(tet_enter > 0, facet_cells(tris, tets), tri_enter > 0)
    assert labels.max() + 1 == shells == gudhi_betti2(centres, radii)
    voxel = flood_fill_voids(centres, radii, step=0.15)
    assert len(voxel) == shells
    facts = dual_facts(AlphaComplex.from_points(centres, weights=radii ** 2))
    ours = region_measures(facts, void_cells(~facts.cell_in, facts.facet_cells, ~facts.facet_in),
                           shells).volume
    # a 0.15 Å voxel grid: within 2 % of the exact volume
    assert np.all(np.abs(np.sort(ours) - np.sort(voxel)) < 0.02 * np.sort(ours))


@pytest.mark.parametrize("alpha2", [-1.0, 0.0, 1.5])
def test_dual_simplices_are_gudhis_at_alpha2(alpha2):
    """dual_simplices (the complex at alpha², read from the enter column, levels k >= 1 as
    prefixes) holds gudhi's simplices with filtration <= alpha², and hands out views."""
    rng = np.random.default_rng(11)
    centres, radii = rng.uniform(0, 9, size=(300, 3)), rng.uniform(0.8, 2.2, size=300)
    ac = AlphaComplex.from_points(centres, weights=radii ** 2)
    ours = dual_simplices(ac, alpha2)
    row_input = np.empty(len(ac.points), np.int64)
    kept = np.flatnonzero(ac.input_index >= 0)
    row_input[ac.input_index[kept]] = kept
    theirs = gudhi_dual(centres, radii)
    for k in range(4):
        simplices, values = theirs[k]
        want = {tuple(s) for s in simplices[values <= alpha2].tolist()}
        got = {tuple(sorted(s)) for s in row_input[ours[k]].tolist()}
        assert got == want
        if k:
            assert np.shares_memory(ours[k], ac.simplices(k))

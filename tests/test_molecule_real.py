"""1A8O through our weighted AlphaComplex: exact SASA and vdW area against freesasa, cavity
count against b2, and `alphascoop info --json`'s molecule object."""

from __future__ import annotations

import json

import numpy as np
import pytest
from scipy.spatial import cKDTree

from app.cli import main
from core.complex import AlphaComplex
from core.io.molecule import read_molecule
from core.molecule.analysis import measure_molecule
from tests.molecule_reference import freesasa_area, monte_carlo_volume, shared_molecule
from tests.reference import DATA_ABSENT

PDB = shared_molecule("1A8O.pdb")
pytestmark = pytest.mark.skipif(PDB is None, reason=DATA_ABSENT)


@pytest.mark.parametrize("probe", [1.4, 0.0])
def test_1a8o_area_matches_freesasa_and_cavities_are_b2(probe):
    mol = read_molecule(PDB)
    ac = AlphaComplex.from_points(mol.centres, weights=mol.weights(probe))
    m = measure_molecule(ac, probe)
    # freesasa's slices converge to the exact value: at 1000 slices 3e-7 of the total away
    total, per_atom = freesasa_area(mol.centres, mol.vdw_radii, slices=1000, probe=probe)
    assert m.surface_area == pytest.approx(total, rel=1e-4)
    assert np.abs(m.atom_area - per_atom).max() < 0.02
    assert len(m.cavities) == ac.betti(alpha2=0.0)[2]
    volume, err = monte_carlo_volume(mol.centres, mol.radii(probe), np.random.default_rng(0))
    assert abs(m.volume - volume) < 5 * err


def test_info_json_molecule_object(capsys):
    assert main(["info", str(PDB), "--json", "--no-cache", "--probe", "1.4"]) == 0
    mol = json.loads(capsys.readouterr().out)["molecule"]
    assert mol["atoms"] == 556 and mol["probe"] == 1.4
    assert len(mol["atom_area"]) == 556
    assert sum(mol["atom_area"]) == pytest.approx(mol["surface_area"], rel=1e-6)
    assert mol["volume"] > 0 and isinstance(mol["cavities"], list)
    assert mol["cavity_errors"] == [0.0] * len(mol["cavities"])  # exact now
    assert len(mol["cavity_areas"]) == len(mol["cavities"])
    pockets = mol["pockets"]
    volumes = [p["volume"] for p in pockets]
    assert len(pockets) > 0 and volumes == sorted(volumes, reverse=True)
    big = pockets[0]
    assert big["area"] > 0 and len(big["mouths"]) >= 1
    assert all(m["area"] >= 0 and m["perimeter"] >= 0 for m in big["mouths"])
    assert {"chain", "residue", "number", "atom", "index"} <= set(big["atoms"][0])
    assert big["atoms"][0]["chain"] == "A" and big["atoms"][0]["residue"].isalpha()
    assert main(["info", str(PDB), "--keep-water", "--no-cache"]) == 0
    text = capsys.readouterr().out
    assert "644 balls" in text and "pockets" in text and "±" not in text


def test_info_molecule_rejects_columns(capsys):
    assert main(["info", str(PDB), "--columns", "x,y,z"]) == 2
    assert "--columns does not apply" in capsys.readouterr().err


def test_export_vtu_carries_atom_area(tmp_path, capsys):
    from core.io import read_points

    out = tmp_path / "1a8o.vtu"
    assert main(["export", str(PDB), "-o", str(out), "--alpha2", "0", "--no-cache"]) == 0
    mol = json.loads(_info_json(capsys))["molecule"]
    area = read_points(out).attributes["atom_area"]  # through meshio
    assert len(area) == 556
    assert area.sum() == pytest.approx(mol["surface_area"], rel=1e-9)


def _info_json(capsys) -> str:
    capsys.readouterr()
    assert main(["info", str(PDB), "--json", "--no-cache"]) == 0
    return capsys.readouterr().out


def test_1a8o_cavities_at_probe_06_against_sampling_in_their_tetrahedra():
    """At probe 0.6 Å 1A8O has voids of a few Å³: each of the two largest against 10^6
    samples of its tetrahedra (empty: in no ball), and its lining area against sphere points
    stepped 10^-6 Å outward into its tetrahedra."""
    from scipy.spatial import cKDTree

    from core.molecule.regions import dual_facts
    from core.molecule.sectors import tet_volumes

    mol = read_molecule(PDB)
    ac = AlphaComplex.from_points(mol.centres, weights=mol.weights(0.6))
    m = measure_molecule(ac, 0.6)
    facts = dual_facts(ac)
    tree, rng = cKDTree(facts.centres), np.random.default_rng(7)
    assert m.cavities[0] > 1.0
    for v in range(2):
        corners = facts.centres[facts.cells[m.cavity_cells == v]]  # (t, 4, 3)
        vol = tet_volumes(corners)
        n = 1_000_000
        cell = rng.choice(len(vol), size=n, p=vol / vol.sum())
        x = np.einsum("pi,pij->pj", rng.dirichlet(np.ones(4), size=n), corners[cell])
        dist, idx = tree.query(x, k=8)
        p = (~(dist <= facts.radii[idx]).any(1)).mean()
        error = vol.sum() * np.sqrt(p * (1 - p) / n)  # about 0.005 Å³
        assert abs(m.cavities[v] - p * vol.sum()) < 4 * error
        atoms = m.cavity_atoms[v]
        counts = np.full(len(atoms), 10_000)
        ball = np.repeat(atoms, counts)
        u = rng.normal(size=(len(ball), 3))
        u /= np.linalg.norm(u, axis=1, keepdims=True)
        y = facts.centres[ball] + (facts.radii[ball, None] + 1e-6) * u
        dist, idx = tree.query(y, k=8)
        free = ~(dist < facts.radii[idx]).any(1)
        inverse = np.linalg.inv(np.transpose(corners[:, 1:] - corners[:, :1], (0, 2, 1)))
        lam = np.einsum("tij,ptj->pti", inverse, y[:, None] - corners[None, :, 0])
        inside = ((lam >= 0).all(2) & (lam.sum(2) <= 1)).any(1)
        sphere = (4 * np.pi * facts.radii[atoms] ** 2 / counts)
        weight = np.repeat(sphere, counts)
        area = float((weight * (free & inside)).sum())
        q = (free & inside).reshape(len(atoms), -1).mean(1)
        error = np.sqrt((sphere ** 2 * counts * q * (1 - q)).sum())
        assert abs(m.cavity_areas[v] - area) < 4 * error + 1e-3


def test_export_pockets_vtu_and_csv(tmp_path, capsys):
    """`export --pockets`: the VTU's cells carry the pocket of each, the CSV the residues
    lining each pocket, both as info --json reports them."""
    import csv

    import meshio

    pockets = json.loads(_info_json(capsys))["molecule"]["pockets"]
    vtu, table = tmp_path / "p.vtu", tmp_path / "p.csv"
    assert main(["export", str(PDB), "-o", str(vtu), "--pockets", "--no-cache"]) == 0
    assert main(["export", str(PDB), "-o", str(table), "--pockets", "--no-cache"]) == 0
    grid = meshio.read(vtu)
    ids = np.concatenate([np.ravel(a) for a in grid.cell_data["pocket"]])
    mouth = np.concatenate([np.ravel(a) for a in grid.cell_data["mouth"]])
    assert set(ids.tolist()) == set(range(len(pockets)))
    n_mouths = sum(len(p["mouths"]) for p in pockets)
    assert len(set(mouth[mouth >= 0].tolist())) == n_mouths
    with open(table, newline="") as handle:
        rows = list(csv.DictReader(handle))
    first = {(r["chain"], r["residue"], r["number"]) for r in rows if r["pocket"] == "0"}
    assert first == {(a["chain"], a["residue"], a["number"]) for a in pockets[0]["atoms"]}
    lining = sum(float(r["lining_area"]) for r in rows if r["pocket"] == "0")
    # the balls with a positive share: a ball's share of one region can be a little below 0
    # (its sector reaching through a neighbour's facet), the region's total is exact
    assert lining == pytest.approx(pockets[0]["area"], rel=0.01)
    assert main(["export", str(PDB), "-o", str(tmp_path / "p.ply"), "--pockets"]) == 2


@pytest.mark.parametrize("probe", [1.4, 0.0])
def test_1a8o_pockets_exact_against_1e7_samples(probe):
    """The four largest pockets' exact volume against 2.5·10^6 uniform samples of each one's
    tetrahedra (10^7 in all; empty: in no ball), within 4 standard errors; every pocket has
    a mouth, the list runs largest first (the lining areas: the next test)."""
    from core.molecule.regions import dual_facts
    from tests.molecule_reference import free_in_tets

    mol = read_molecule(PDB)
    ac = AlphaComplex.from_points(mol.centres, weights=mol.weights(probe))
    pockets = measure_molecule(ac, probe).pockets
    facts = dual_facts(ac)
    assert np.all(np.diff(pockets.volume) <= 0)
    assert set(pockets.mouth_pocket.tolist()) == set(range(len(pockets)))
    rng = np.random.default_rng(3)
    for p in range(4):
        corners = facts.centres[facts.cells[pockets.cells == p]]
        volume, error = free_in_tets(corners, facts.centres, facts.radii, 2_500_000, rng)
        assert abs(pockets.volume[p] - volume) < 4 * error


@pytest.mark.parametrize("probe", [1.4, 0.0])
def test_1a8o_lining_area_of_every_ball_of_the_largest_pocket_against_sampling(probe):
    """Each ball's lining area of the largest pocket (its row of pockets.atom_area) against
    50 uniform points per Å² of its sphere that lie in no other ball (every ball asked) and
    inside the pocket's tetrahedra. Asked of every ball whose sphere can reach one of those
    tetrahedra (their bounding spheres), lining or not: each within 4.5 binomial standard
    errors of our value plus one point's area (a right answer fails one of the 150-550
    balls with a chance under 0.4%), the pocket's total within 4."""
    from core.molecule.regions import dual_facts
    from core.query.locate import Locator
    from tests.molecule_reference import exposed_points

    mol = read_molecule(PDB)
    ac = AlphaComplex.from_points(mol.centres, weights=mol.weights(probe))
    pockets = measure_molecule(ac, probe).pockets
    facts = dual_facts(ac)
    mine = np.flatnonzero(pockets.cells == 0)
    corners = facts.centres[facts.cells[mine]]  # (t, 4, 3)
    middle = corners.mean(1)
    bound = np.linalg.norm(corners - middle[:, None], axis=2).max(1)
    near = np.unique(np.concatenate(cKDTree(facts.centres).query_ball_point(
        middle, bound + facts.radii.max())).astype(np.int64))
    near = near[(np.linalg.norm(facts.centres[near, None] - middle, axis=2)
                 <= bound + facts.radii[near, None]).any(1)]
    sphere = 4 * np.pi * facts.radii[near] ** 2
    counts = (50 * sphere).astype(np.int64)
    ball = np.repeat(near, counts)
    rng = np.random.default_rng(5)
    u = rng.normal(size=(len(ball), 3))
    u /= np.linalg.norm(u, axis=1, keepdims=True)
    y = facts.centres[ball] + facts.radii[ball, None] * u
    hit = exposed_points(y, ball, facts.centres, facts.radii)
    cell = Locator(facts.centres, facts.cells, ac.face_ids(3), facts.facet_cells).locate(y[hit])
    held = y[hit][cell >= 0]
    around = facts.centres[facts.cells[cell[cell >= 0]]]
    lam = np.linalg.solve(np.transpose(around[:, 1:] - around[:, :1], (0, 2, 1)),
                          (held - around[:, 0])[..., None])[..., 0]
    assert (lam >= -1e-9).all() and (lam.sum(1) <= 1 + 1e-9).all()  # the cell holds it
    hit[hit] = np.isin(cell, mine)  # -1 (outside the hull) is in no pocket
    sampled = sphere * np.bincount(np.repeat(np.arange(len(near)), counts), weights=hit,
                                   minlength=len(near)) / counts
    ours = pockets.atom_area[0].toarray().ravel()[near]
    share = np.clip(ours / sphere, 0, 1)
    error = sphere * np.sqrt(share * (1 - share) / counts)
    assert np.all(np.abs(ours - sampled) <= 4.5 * error + sphere / counts)
    assert set(pockets.atoms[0].tolist()) <= set(near.tolist())
    assert abs(pockets.area[0] - sampled.sum()) < 4 * np.sqrt((error ** 2).sum())

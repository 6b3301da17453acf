"""Molecule reader: PDB and mmCIF of one entry give the same atoms; models, altlocs, waters,
gzip, unknown elements and bad files."""

from __future__ import annotations

import gzip
import shutil

import numpy as np
import pytest

from core.errors import FileFormatError
from core.io import read_points
from core.io.molecule import UNKNOWN_RADIUS, read_molecule
from tests.molecule_reference import shared_molecule
from tests.reference import DATA_ABSENT

PDB, CIF = shared_molecule("1A8O.pdb"), shared_molecule("1A8O.cif")
needs_data = pytest.mark.skipif(PDB is None, reason=DATA_ABSENT)

TWO_MODELS = """\
MODEL        1
ATOM      1  N   ALA A   1       0.000   0.000   0.000  1.00  0.00           N
ATOM      2  CA AALA A   1       1.458   0.000   0.000  0.60  0.00           C
ATOM      3  CA BALA A   1       1.500   0.100   0.000  0.40  0.00           C
ATOM      4  H   ALA A   1      -0.500   0.800   0.000  1.00  0.00           H
HETATM    5  O   HOH A 101       3.000   3.000   3.000  1.00  0.00           O
HETATM    6 XX   UNL A 102       5.000   0.000   0.000  1.00  0.00           X
ENDMDL
MODEL        2
ATOM      1  N   ALA A   1       9.000   0.000   0.000  1.00  0.00           N
ENDMDL
END
"""


@needs_data
def test_pdb_and_cif_give_the_same_atoms():
    pdb, cif = read_molecule(PDB), read_molecule(CIF)
    assert pdb.report.atoms == cif.report.atoms == 556  # 524 ATOM + 32 MSE, no water
    assert np.array_equal(pdb.centres, cif.centres)
    assert np.array_equal(pdb.elements, cif.elements)
    assert np.array_equal(pdb.vdw_radii, cif.vdw_radii)
    assert np.array_equal(pdb.residues, cif.residues)
    assert pdb.report.waters_skipped == 88
    assert read_molecule(PDB, keep_water=True).report.atoms == 556 + 88


@needs_data
def test_gzip_and_point_reader(tmp_path):
    gz = tmp_path / "1a8o.cif.gz"
    with open(CIF, "rb") as src, gzip.open(gz, "wb") as dst:
        shutil.copyfileobj(src, dst)
    assert np.array_equal(read_molecule(gz).centres, read_molecule(PDB).centres)
    ps = read_points(gz)
    assert len(ps.points) == 556 and ps.report.format == "CIF"
    mol = read_molecule(PDB)
    assert np.array_equal(ps.points, mol.centres)  # no duplicates: the same rows
    assert np.allclose(ps.attributes["weights"], (mol.vdw_radii + 1.4) ** 2)


def test_first_model_first_altloc_hydrogens_unknown(tmp_path):
    path = tmp_path / "small.pdb"
    path.write_text(TWO_MODELS)
    mol = read_molecule(path)
    r = mol.report
    assert (r.models, r.atoms, r.altlocs_skipped, r.waters_skipped, r.hydrogens) == (2, 4, 1, 1, 1)
    assert mol.centres[1].tolist() == [1.458, 0.0, 0.0]  # altloc A
    assert mol.vdw_radii.tolist() == [1.55, 1.7, 1.2, UNKNOWN_RADIUS]
    assert r.unknown_elements == ("X",)
    assert np.allclose(mol.weights(1.4), (mol.vdw_radii + 1.4) ** 2)


@pytest.mark.parametrize(("name", "text"), [
    ("garbage.cif", "data_x\nloop_\n_atom_site.id\n'unterminated\n"),
    ("binary.cif", "\x00\x01\x02 not a cif"),
    ("empty_model.pdb", "HEADER    NOTHING\nEND\n"),
    ("water_only.pdb", "HETATM    1  O   HOH A   1       0.000   0.000   0.000  1.00  0.00"
                       "           O\nEND\n"),
])
def test_bad_files_are_one_line_errors(tmp_path, name, text):
    path = tmp_path / name
    path.write_text(text)
    with pytest.raises(FileFormatError) as err:
        read_molecule(path)
    assert str(path) in str(err.value) and "\n" not in str(err.value)
    with pytest.raises(FileFormatError):
        read_points(path)


def test_report_summary_counts_in_words():
    """One chain is "1 chain", not "1 chains"."""
    from core.io.molecule import MoleculeReport

    one = MoleculeReport(path="m.pdb", models=1, chains=1, residues=1, atoms=1, hydrogens=0,
                         waters_skipped=0, altlocs_skipped=0)
    assert one.summary().startswith("1 atom (0 H), 1 residue, 1 chain, model 1 of 1;")
    two = MoleculeReport(path="m.pdb", models=2, chains=2, residues=70, atoms=1556, hydrogens=0,
                         waters_skipped=0, altlocs_skipped=0)
    assert two.summary().startswith("1,556 atoms (0 H), 70 residues, 2 chains, model 1 of 2;")

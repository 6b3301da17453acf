"""PQR and XYZR readers: the file's radii, residues and atom names; 1A8O written as PQR and
XYZR gives freesasa's area for those radii; bad lines are one-line errors."""

from __future__ import annotations

import html
import json

import numpy as np
import pytest

from app.cli import main
from core.complex import AlphaComplex
from core.errors import FileFormatError
from core.io import read_points
from core.io.molecule import read_molecule
from core.molecule.analysis import measure_molecule
from tests.molecule_reference import freesasa_area, shared_molecule
from tests.reference import DATA_ABSENT

PDB = shared_molecule("1A8O.pdb")
needs_data = pytest.mark.skipif(PDB is None, reason=DATA_ABSENT)

PQR = """\
REMARK   written by PDB2PQR
ATOM      1  N   ALA A   1       0.000   0.000   0.000 -0.3000 1.8240
ATOM      2  CA  ALA A   1       1.458   0.000   0.000  0.0300 1.9080
ATOM      3  O   HOH     2       3.000   3.000   3.000 -0.8340 1.7683
ATOM      4  SG  CYS    7      -1.000   2.000   0.500 -0.3100 2.0000
ENDMDL
ATOM      5  N   ALA A   1       9.000   0.000   0.000 -0.3000 1.8240
"""


def test_pqr_radii_residues_names_and_waters(tmp_path):
    path = tmp_path / "x.pqr"
    path.write_text(PQR)
    mol = read_molecule(path)
    assert mol.vdw_radii.tolist() == [1.824, 1.908, 2.0]  # water skipped, first model only
    assert mol.residues.tolist() == ["A:ALA:1", "A:ALA:1", ":CYS:7"]
    assert mol.atom_names.tolist() == ["N", "CA", "SG"]
    assert mol.elements.tolist() == ["N", "C", "S"] and mol.report.waters_skipped == 1
    assert len(read_molecule(path, keep_water=True).vdw_radii) == 4
    ps = read_points(path)
    assert np.allclose(ps.attributes["weights"], (mol.vdw_radii + 1.4) ** 2)


def test_xyzr_radii_and_comments(tmp_path):
    path = tmp_path / "x.xyzr"
    path.write_text("# MSMS\n0 0 0 1.5\n2.5 0 0 1.7 CA\n\n0 2 0 1.2  # last\n")
    mol = read_molecule(path)
    assert mol.vdw_radii.tolist() == [1.5, 1.7, 1.2]
    assert mol.centres.tolist() == [[0, 0, 0], [2.5, 0, 0], [0, 2, 0]]
    # an XYZR file has no residues or chains: the note does not count one per atom
    assert mol.report.summary().startswith("3 atoms (0 H), no residues or chains in the file,")


@pytest.mark.parametrize(("name", "text", "words"), [
    ("a.pqr", "ATOM 1 N ALA A 1 0 0 0\n", "10 or 11 fields"),
    ("b.pqr", "ATOM 1 N ALA A 1 0 0 x -0.3 1.8\n", "must be numbers"),
    ("c.pqr", "ATOM 1 N ALA A 1 0 0 0 -0.3 0\n", "positive number"),
    ("d.pqr", "REMARK nothing\n", "no atoms"),
    ("e.xyzr", "0 0 zero 1\n", "x y z radius"),
    ("f.xyzr", "0 0 0 nan\n", "positive number"),
])
def test_bad_radii_files_are_one_line_errors(tmp_path, name, text, words):
    path = tmp_path / name
    path.write_text(text)
    with pytest.raises(FileFormatError, match=words):
        read_molecule(path)


def _write(mol, path, kind):
    with open(path, "w") as out:
        for i, (c, r) in enumerate(zip(mol.centres, mol.vdw_radii, strict=True)):
            chain, res, num = mol.residues[i].split(":")
            if kind == "pqr":
                out.write(f"ATOM  {i + 1:5d} {mol.atom_names[i]:<4} {res} {chain} {num} "
                          f"{c[0]:.3f} {c[1]:.3f} {c[2]:.3f} 0.0000 {r:.4f}\n")
            else:
                out.write(f"{c[0]:.3f} {c[1]:.3f} {c[2]:.3f} {r:.4f}\n")


@needs_data
@pytest.mark.parametrize("kind", ["pqr", "xyzr"])
def test_1a8o_as_radii_file_matches_freesasa(tmp_path, kind, capsys):
    """Radii changed in the file (x 1.1) are the ones measured: freesasa's area with them."""
    mol = read_molecule(PDB)
    scaled = type(mol)(mol.centres, mol.elements, mol.atomic_numbers, mol.vdw_radii * 1.1,
                       mol.residues, mol.report, mol.atom_names)
    path = tmp_path / f"1a8o.{kind}"
    _write(scaled, path, kind)
    read = read_molecule(path)
    assert np.allclose(read.vdw_radii, np.round(mol.vdw_radii * 1.1, 4))
    ac = AlphaComplex.from_points(read.centres, weights=read.weights(1.4))
    total, _ = freesasa_area(read.centres, read.vdw_radii, slices=1000, probe=1.4)
    assert measure_molecule(ac, 1.4).surface_area == pytest.approx(total, rel=1e-4)
    assert main(["info", str(path), "--json", "--no-cache"]) == 0
    info = json.loads(capsys.readouterr().out)["molecule"]
    assert info["surface_area"] == pytest.approx(total, rel=1e-4)
    if kind == "pqr":
        assert info["pockets"][0]["atoms"][0]["residue"].isalpha()
    table = tmp_path / "pockets.csv"  # an XYZR file has no residues: its rows are atoms
    assert main(["export", str(path), "-o", str(table), "--pockets"]) == 0
    lining = "residues" if kind == "pqr" else "atoms"
    assert capsys.readouterr().out.endswith(f" lining {lining}\n")


@pytest.mark.parametrize(("name", "radii"), [("m.pqr", "the file's radii"),
                                             ("m.xyzr", "the file's radii"),
                                             ("m.pdb.gz", "van der Waals radii (Bondi)")])
def test_info_dock_names_where_the_radii_came_from(name, radii):
    """A PQR or XYZR file brings its own radii: the info dock does not call them Bondi's."""
    from types import SimpleNamespace

    from app.info_panel import weights_line

    ds = SimpleNamespace(is_molecule=True, probe=1.4, path=name,
                         ac=SimpleNamespace(input_index=np.arange(3)))
    assert weights_line(ds) == html.escape(f"atoms as balls: {radii} + probe 1.4 Å")


def test_pocket_text_of_atoms_without_residues():
    """A pocket of an XYZR file (no chains, no residue names) lists its atoms' numbers, not
    "residues" padded with the empty names."""
    from app.pockets_layer import pocket_text

    class OnePocket:
        volume, area, mouth_area, atoms = [55.0], [62.3], [32.0], [[1, 0]]

        def mouths(self, pocket):
            return [0]

        def __len__(self):
            return 1

    pockets = OnePocket()
    xyzr = pocket_text(pockets, 0, np.array(["::1:", "::2:"]))
    assert xyzr.endswith("<br>2 atoms: 2, 1")
    pdb = pocket_text(pockets, 0, np.array(["A:CYS:218:SG", "A:GLY:220:CA"]))
    assert pdb.endswith("<br>2 residues: A GLY 220, A CYS 218")

"""Molecule files keep every atom but those of alternate conformations other than the kept
one: atoms that merely share a name within a residue (ligands written with element names,
no altloc) all stay; a real altloc file loses exactly its B atoms."""

from __future__ import annotations

from pathlib import Path

import gemmi
import numpy as np
import pytest

from core.io.molecule import read_molecule

DATA = Path(__file__).parent / "data" / "molecules"


def element_named_ligand(folder: Path) -> Path:
    """gemmi_HEM.pdb as docking and conversion tools write ligands: HETATM records whose
    atom names are the element symbols (so 34 carbons are all 'C'), no altloc."""
    lines = []
    for line in (DATA / "gemmi_HEM.pdb").read_text().splitlines():
        if line.startswith("ATOM  "):
            element = line[76:78].strip()
            line = f"HETATM{line[6:12]} {element:<3}{line[16:]}"
        lines.append(line)
    path = folder / "hem_element_names.pdb"
    path.write_text("\n".join(lines) + "\n")
    return path


def _atom_records(path: Path) -> list[str]:
    return [line for line in path.read_text().splitlines()
            if line.startswith(("ATOM  ", "HETATM"))]


def test_ligand_atoms_sharing_a_name_all_stay(tmp_path):
    path = element_named_ligand(tmp_path)
    records = _atom_records(path)
    names = [line[12:16].strip() for line in records]
    assert len(records) == 75 and names.count("C") == 34  # the names really repeat
    mol = read_molecule(path)
    assert mol.report.atoms == 75 and mol.report.altlocs_skipped == 0
    want = np.array([[float(line[30:38]), float(line[38:46]), float(line[46:54])]
                     for line in records])
    np.testing.assert_allclose(mol.centres, want, atol=5e-4)


def test_an_mmcif_ligand_sharing_names_keeps_every_atom(tmp_path):
    st = gemmi.read_structure(str(element_named_ligand(tmp_path)))
    st.setup_entities()
    path = tmp_path / "hem_element_names.cif"
    st.make_mmcif_document().write_file(str(path))
    mol = read_molecule(path)
    assert mol.report.atoms == 75 and mol.report.altlocs_skipped == 0


def test_one_residue_of_repeated_names_keeps_every_atom(tmp_path):
    """A protein fragment dumped as one residue (every atom numbered 1), no altloc."""
    lines = [f"HETATM{line[6:17]}LIG A   1{line[26:]}"
             for line in _atom_records(DATA / "gemmi_4hhh_frag.pdb") if line[16] == " "]
    path = tmp_path / "one_residue.pdb"
    path.write_text("\n".join(lines) + "\nEND\n")
    mol = read_molecule(path)
    assert mol.report.atoms == len(lines) == 85 and mol.report.altlocs_skipped == 0


def test_real_alternate_locations_keep_the_first_conformer():
    path = DATA / "gemmi_4hhh_frag.pdb"
    records = _atom_records(path)
    altloc = [line[16] for line in records]
    assert len(records) == 97 and altloc.count("A") == altloc.count("B") == 6
    mol = read_molecule(path)
    assert mol.report.atoms == 91 and mol.report.altlocs_skipped == 6
    kept = [line for line in records if line[16] in " A"]
    want = np.array([[float(line[30:38]), float(line[38:46]), float(line[46:54])]
                     for line in kept])
    np.testing.assert_allclose(mol.centres, want, atol=5e-4)


@pytest.mark.parametrize("altloc", ["A", "B"])
def test_a_conformer_alone_is_kept_whole(tmp_path, altloc):
    """A file holding one conformer only (altloc B set, no A): nothing is dropped."""
    lines = [line for line in _atom_records(DATA / "gemmi_4hhh_frag.pdb")
             if line[16] in (" ", altloc)]
    path = tmp_path / "one_conformer.pdb"
    path.write_text("\n".join(lines) + "\nEND\n")
    mol = read_molecule(path)
    assert mol.report.atoms == 91 and mol.report.altlocs_skipped == 0

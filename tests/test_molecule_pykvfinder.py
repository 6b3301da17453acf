"""Our pockets beside pyKVFinder's cavities (a grid method with another definition) on 1A8O:
the largest found by both line the same residues (assets/docs/pockets.md says where they differ)."""

from __future__ import annotations

import logging

import pytest

from core.complex import AlphaComplex
from core.io.molecule import atom_labels, read_molecule
from core.molecule.analysis import measure_molecule
from tests.molecule_reference import shared_molecule
from tests.reference import COMPARE_EXTRA, DATA_ABSENT

PDB = shared_molecule("1A8O.pdb")
pytestmark = pytest.mark.skipif(PDB is None, reason=DATA_ABSENT)


def _kvfinder_residues(tmp_path) -> list[set]:
    """pyKVFinder's cavities (default parameters) on 1A8O without its waters, largest first:
    each a set of (chain, residue number)."""
    kv = pytest.importorskip("pyKVFinder", reason=COMPARE_EXTRA)
    dry = tmp_path / "1a8o_dry.pdb"
    dry.write_text("".join(line for line in PDB.read_text().splitlines(keepends=True)
                           if not (line.startswith("HETATM") and "HOH" in line)))
    logging.disable(logging.WARNING)  # pyKVFinder logs each atom radius it guesses
    try:
        result = kv.run_workflow(str(dry))
    finally:
        logging.disable(logging.NOTSET)
    order = sorted(result.volume, key=result.volume.get, reverse=True)
    return [{(chain, number) for number, chain, _ in result.residues[k]} for k in order]


def test_largest_pockets_overlap_pykvfinder(tmp_path):
    theirs = _kvfinder_residues(tmp_path)
    assert theirs
    mol = read_molecule(PDB)
    ac = AlphaComplex.from_points(mol.centres, weights=mol.weights(1.4))
    pockets = measure_molecule(ac, 1.4).pockets
    labels = atom_labels(mol, ac.points)
    ours = [{(labels[a]["chain"], labels[a]["number"]) for a in pockets.atoms[p]}
            for p in range(min(3, len(pockets)))]
    # pyKVFinder's largest cavity is lined by the same residues as one of our three largest
    # pockets: every residue of ours is among its own (10 of 10), Jaccard index 0.59
    best = max(ours, key=lambda mine: len(mine & theirs[0]) / len(mine | theirs[0]))
    assert len(best & theirs[0]) >= 0.9 * len(best)
    assert len(best & theirs[0]) / len(best | theirs[0]) >= 0.5

"""The window on a molecule: atoms as CPK-coloured balls, cavities at the current alpha, the
exact measures in the info dock."""

from __future__ import annotations

import numpy as np
import pytest
from conftest import open_and_wait

from app.palette import cpk_rgb
from app.signatures_dock import MIN_PLOT_HEIGHT
from core.molecule.cavities import cavity_cells
from tests.molecule_reference import shared_molecule
from tests.reference import DATA_ABSENT

PDB = shared_molecule("1A8O.pdb")
pytestmark = [pytest.mark.gui,
              pytest.mark.skipif(PDB is None, reason=DATA_ABSENT)]


def test_cpk_colours():
    rgb = cpk_rgb(np.array([6, 7, 8, 16, 99]))
    assert rgb.tolist() == [[144, 144, 144], [48, 80, 248], [255, 13, 13], [255, 255, 48],
                            [255, 20, 147]]


def test_molecule_window(window, qtbot, recwarn):
    open_and_wait(qtbot, window, PDB)
    ds, model = window.model.dataset, window.model
    assert ds.molecule is not None and ds.molecule.atoms == 556
    # opens on the dual of the union of balls (what it measures): at alpha² = 0 itself (the
    # slider stands there), the complex of the last critical alpha² at or below 0
    assert model.alpha2 == 0.0
    critical = ds.ac.spectrum_sq()
    below = critical[np.searchsorted(critical, 0.0, "right") - 1]
    assert len(model.shape.cells) == len(ds.ac.shape(alpha2=below).cells)
    assert ds.molecule.surface_area == pytest.approx(4668.88, abs=0.01)
    text = window.info_panel.data.text()
    assert "4,668.88 Å²" in text and "14,036.46 Å³" in text and "2 cavities" in text
    assert "van der Waals radii (Bondi) + probe 1.4 Å" in text
    assert "weight column" not in text and "-1" not in text  # no internal sentinel
    shape_text = window.info_panel.shape.text()
    assert "<b>alpha² 0 Å² (alpha 0 Å)</b>" in shape_text and " Å³" in shape_text
    balls = window.scene.meshes["balls"]
    colours = {tuple(c) for c in np.asarray(balls.point_data["rgb"])}
    assert {(144, 144, 144), (255, 13, 13), (48, 80, 248)} <= colours  # C, O, N
    assert window.scene.layers["balls"].actor.GetVisibility()
    mapper = window.scene.layers["balls"].actor.mapper  # drawn in those element colours
    assert mapper.GetScalarVisibility() and mapper.GetArrayName() == "rgb"
    window.scene.render()  # a still view draws only the outer balls it shows
    qtbot.wait(50)
    layer = window.scene.layers["balls"]
    assert 0 < mapper.GetInput().GetNumberOfPoints() < 0.6 * layer.outer.n_points
    model.set_alpha2(0.0)
    qtbot.wait(50)
    cavities = window.scene.meshes["cavities"]
    expected = cavity_cells(ds.ac, model.alpha2)
    assert len(expected) > 0 and cavities.n_cells == len(expected)
    model.set_index(len(model.spectrum) - 1)  # the hull: no cavities
    qtbot.wait(50)
    assert window.scene.meshes["cavities"].n_cells == 0
    canvas = window.signatures_panel.canvas
    canvas.draw()  # the signatures dock keeps room for its axes (no collapsed layout)
    assert canvas.height() >= MIN_PLOT_HEIGHT
    assert not [w for w in recwarn if "constrained_layout" in str(w.message)]


def test_pockets_layer_colours_and_click(window, qtbot, tmp_path):
    """The pockets are a layer of their tetrahedra, one colour per pocket, with their mouths;
    clicking a pocket's cell lists its residues in the Inspect dock."""
    open_and_wait(qtbot, window, PDB)
    ds = window.model.dataset
    pockets = ds.molecule.pockets
    assert len(pockets) >= 2
    mesh = window.scene.meshes["pockets"]
    assert mesh.n_cells == int((pockets.cells >= 0).sum())
    rgb = np.asarray(mesh.cell_data["rgb"])
    assert len({tuple(c) for c in rgb}) == min(len(pockets), 10)
    assert window.scene.meshes["mouths"].n_cells == len(pockets.facets)
    mapper = window.scene.layers["pockets"].actor.mapper
    assert mapper.GetScalarVisibility() and mapper.GetArrayName() == "rgb"
    assert "pockets" in window.layers_panel.rows and "mouths" in window.layers_panel.rows
    window.model.set_index(len(window.model.spectrum) - 1)  # a new alpha keeps the pockets
    qtbot.wait(50)
    assert window.scene.meshes["pockets"].n_cells == mesh.n_cells
    cell = int(np.flatnonzero(pockets.cells == 0)[0])
    window.inspector.inspect_vertices(ds.ac.simplices(3)[cell])
    text = window.inspect_panel.fields["pocket"].text()
    first = ds.atom_labels[pockets.atoms[0][0]].split(":")
    assert "pocket 1 of" in text and " ".join(first[:3]) in text
    window.inspector.inspect_vertices(ds.ac.simplices(0)[0])  # a vertex: no pocket
    assert window.inspect_panel.fields["pocket"].text() == ""


def test_export_pockets_from_the_window(window, qtbot, tmp_path, monkeypatch):
    """File → Export pockets writes the VTU (cell data pocket) and the CSV of residues."""
    import csv

    import meshio

    from app import file_actions

    open_and_wait(qtbot, window, PDB)
    pockets = window.model.dataset.molecule.pockets
    for name in ("p.vtu", "p.csv"):
        monkeypatch.setattr(file_actions, "ask_save_path", lambda *_a, n=name: tmp_path / n)
        window.menus["export_pockets"].trigger()
    ids = np.concatenate([np.ravel(a) for a in meshio.read(tmp_path / "p.vtu").cell_data["pocket"]])
    assert set(ids.tolist()) == set(range(len(pockets)))
    with open(tmp_path / "p.csv", newline="") as handle:
        rows = list(csv.DictReader(handle))
    assert {r["pocket"] for r in rows} == {str(p) for p in range(len(pockets))}
    assert rows[0]["chain"] == "A" and rows[0]["residue"].isalpha() and rows[0]["atoms"]

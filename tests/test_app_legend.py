"""The scene's legend on real scans at their opening alpha: surface, singular edges and
singular points each in a colour of their own, each with a row that counts what is drawn."""

from __future__ import annotations

from pathlib import Path

import pytest

from app.dataset import load_dataset
from app.palette import default_styles
from app.scene import Scene, scene_data
from core.complex import at_value

CORPUS = Path(__file__).resolve().parent / "data" / "corpus"
pytestmark = pytest.mark.gui


@pytest.fixture
def scene():
    """An off-screen scene, closed afterwards."""
    made = Scene.off_screen((640, 400))
    yield made
    made.close()


def test_each_class_has_its_colour_and_a_counted_row(scene, tmp_path, monkeypatch) -> None:
    """pdal_test.pts (a sparse scan) opens with dust: its singular points and edges are
    named apart from the surface, with their counts (they shared the surface's colour and
    one legend row)."""
    monkeypatch.setenv("ALPHASCOOP_CACHE_DIR", str(tmp_path / "cache"))
    dataset = load_dataset(CORPUS / "text" / "pdal_test.pts", lambda *_: None)
    scene.set_dataset(scene_data(dataset, default_styles(3)))
    shape = dataset.ac.shape(**at_value(dataset.default_alpha))
    scene.set_shape(shape)
    colours = {name: scene.styles[name].colour
               for name in ("surface", "singular_edges", "singular_points")}
    assert len(set(colours.values())) == 3
    rows = dict((swatch, text) for text, swatch in scene.overlay.entries)
    surface = len(shape.singular(2)) + len(shape.regular_facets)
    points, edges = len(shape.singular(0)), len(shape.singular(1))
    assert points > 0 and edges > 0  # a sparse scan at its opening alpha
    assert rows[colours["surface"]] == f"Surface: {surface:,} triangles"
    assert rows[colours["singular_edges"]] == f"Singular edges: {edges:,}"
    assert rows[colours["singular_points"]] == f"Singular points: {points:,}"
    legend = scene.overlay.legend
    scene.set_shape(dataset.ac.shape(**at_value(dataset.spectrum[-1])))  # the hull
    assert scene.overlay.legend is legend  # rows rewritten in place, not a new actor
    assert dict((s, t) for t, s in scene.overlay.entries)[colours["singular_points"]] == (
        "Singular points: 0")

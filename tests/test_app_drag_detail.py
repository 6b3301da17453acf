"""Dragging the slider draws a lighter frame (fewer cells, no multisampling) that keeps up;
its release draws the full frame at the alpha it stopped on: no thinned frame stays."""

from __future__ import annotations

import pytest
from conftest import open_and_wait

from app.resources import SAMPLE_PATH
from app.scene.layers import shape_cells

pytestmark = pytest.mark.gui
LIMIT = 40  # cells a layer draws while dragging, in this test


def test_drag_thins_the_layers_and_release_restores_the_full_frame(window, qtbot) -> None:
    open_and_wait(qtbot, window, SAMPLE_PATH)
    scene, model, slider = window.scene, window.model, window.alpha_panel.slider
    scene.lod_limit = LIMIT
    samples = scene.plotter.render_window.GetMultiSamples()
    model.set_index(model.hull_index() - 1)  # many surface triangles
    qtbot.wait(10)
    assert len(shape_cells(model.shape, "surface")) > 4 * LIMIT
    slider.setSliderDown(True)
    for offset in (30, 60, 90):
        slider.setSliderPosition(slider.value() - offset)  # a drag: sliderMoved, valueChanged
        qtbot.wait(10)
    drawn = scene.layers["surface"].mesh.n_cells
    full = len(shape_cells(model.shape, "surface"))
    assert 0 < drawn <= LIMIT < full
    assert scene.plotter.render_window.GetMultiSamples() == 0
    slider.setSliderDown(False)  # the release
    qtbot.wait(10)
    assert scene.layers["surface"].mesh.n_cells == len(shape_cells(model.shape, "surface"))
    assert scene.plotter.render_window.GetMultiSamples() == samples

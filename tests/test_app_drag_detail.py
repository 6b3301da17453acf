"""Dragging the slider draws a lighter frame (fewer cells, thin lines, flat points, no
anti-aliasing) that keeps up; its release draws the full frame at the alpha it stopped on,
once: no thinned frame, nor one of an older alpha, stays."""

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
    renderer, render_window = scene.plotter.renderer, scene.plotter.render_window
    assert renderer.GetUseFXAA()  # the window's full frame is smoothed
    edges = scene.layers["singular_edges"].actor.prop
    width = edges.line_width
    points = scene.layers["singular_points"].actor.GetProperty()
    assert points.GetRenderPointsAsSpheres()  # the full frame's round points
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
    assert render_window.GetMultiSamples() == 0 and not renderer.GetUseFXAA()
    assert edges.line_width == 1 < width
    assert not points.GetRenderPointsAsSpheres()  # flat squares while dragging
    slider.setSliderDown(False)  # the release
    qtbot.wait(10)
    assert scene.layers["surface"].mesh.n_cells == len(shape_cells(model.shape, "surface"))
    assert renderer.GetUseFXAA() and edges.line_width == width
    assert points.GetRenderPointsAsSpheres()


def test_a_release_draws_one_full_frame_at_the_released_alpha(window, qtbot) -> None:
    """A release that comes before the last move's frame (a mouse's last move and release
    often arrive together) draws the full frame once, at the alpha released on: no frame of
    an older alpha or of the thinned drag is drawn after it, nor left on screen."""
    open_and_wait(qtbot, window, SAMPLE_PATH)
    scene, model, panel = window.scene, window.model, window.alpha_panel
    slider = panel.slider
    scene.lod_limit = LIMIT
    model.set_index(model.hull_index() - 1)
    qtbot.wait(10)
    frames = []  # (alpha index, surface cells drawn) of every render

    def drawn(*_) -> None:
        frames.append((model.index, scene.layers["surface"].mesh.n_cells))

    scene.plotter.render_window.AddObserver("EndEvent", drawn)
    slider.setSliderDown(True)
    slider.setSliderPosition(slider.value() - 30)
    qtbot.wait(10)
    assert frames and frames[-1][1] <= LIMIT  # the drag's thinned frame
    released = slider.value() - 60
    slider.setSliderPosition(released)  # the last move, its frame not drawn yet...
    slider.setSliderDown(False)  # ...when the release comes
    del frames[:]
    qtbot.wait(200)
    index = panel.travel.index_at(released)
    full = len(shape_cells(model.shape, "surface"))
    assert model.index == index
    assert frames == [(index, full)]  # one frame, full, at the released alpha
    assert scene.layers["surface"].mesh.n_cells == full


def test_a_drag_move_is_painted_at_its_alpha_in_one_pass(window, qtbot) -> None:
    """A drag move paints the window once (a paint composes all of it in software GL), at the
    alpha moved to: the slider's new place and its shape together, the texts the step changed
    laid out before that paint rather than painted again after it."""
    from PySide6.QtCore import QEvent, QObject

    open_and_wait(qtbot, window, SAMPLE_PATH)
    model, slider = window.model, window.alpha_panel.slider
    model.set_index(model.hull_index() - 1)
    qtbot.wait(50)
    paints = []  # the model's alpha index at each paint of the window

    class Paints(QObject):
        def eventFilter(self, watched, event) -> bool:
            if watched is window and event.type() == QEvent.Type.UpdateRequest:
                paints.append(model.index)
            return False

    watcher = Paints()
    window.installEventFilter(watcher)
    slider.setSliderDown(True)
    try:
        for offset in (200, 400, 600):
            before = model.index
            del paints[:]
            slider.setSliderPosition(slider.value() - offset // 2)
            qtbot.wait(60)
            assert model.index != before
            assert paints == [model.index]
    finally:
        slider.setSliderDown(False)
        window.removeEventFilter(watcher)

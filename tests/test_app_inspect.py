"""Inspect: a click in the view picks a shown simplex; the dock shows the table's vertices,
intervals and class; the spoon is drawn on request. Clicks are real Qt mouse events on the
view, so they take the same path as a user's."""

from __future__ import annotations

import numpy as np
import pytest
from conftest import open_and_wait
from PySide6.QtCore import QPoint, Qt

from app.inspect import alpha_text
from app.palette import default_styles
from core.query.classes import CLASSES


def blobs(dim: int, n: int = 900, seed: int = 5) -> np.ndarray:
    """(n, dim) two noisy clusters: solid parts, singular bits."""
    rng = np.random.default_rng(seed)
    return np.concatenate([rng.normal(size=(n // 2, dim)),
                           0.5 * rng.normal(size=(n - n // 2, dim)) + 4.0])


@pytest.fixture(params=[3, 2], ids=["3d", "2d"])
def opened(request, window, qtbot, tmp_path):
    """A window showing blobs of the given dimension at the optimal alpha, interior shown."""
    path = tmp_path / f"blobs{request.param}.npy"
    np.save(path, blobs(request.param))
    open_and_wait(qtbot, window, path)
    window.layers_panel._edit("interior", visible=True,
                              opacity=default_styles(request.param)["interior"].opacity)
    window.scene.plotter.render()
    return window


def surface(win) -> str:
    """The layer that draws the shape's surface: triangles in 3D, boundary edges in 2D."""
    return "surface" if win.model.dataset.ac.dim == 3 else "boundary"


def display_point(win, world: np.ndarray) -> tuple[float, float]:
    """Display coordinates (pixels, origin bottom left) of a world point in the view."""
    renderer = win.scene.plotter.renderer
    renderer.SetWorldPoint(*world, 1.0)
    renderer.WorldToDisplay()
    x, y, _ = renderer.GetDisplayPoint()
    return x, y


def click_view(win, qtbot, x: float, y: float) -> None:
    """A left click (press and release, no drag) on the view at display (x, y)."""
    widget = win.scene.plotter
    ratio = widget.devicePixelRatioF()
    pos = QPoint(round(x / ratio), round(widget.height() - 1 - y / ratio))
    qtbot.mouseClick(widget, Qt.MouseButton.LeftButton, pos=pos)
    qtbot.wait(20)  # the pick runs once the release event is over


def visible_target(win, layer: str) -> np.ndarray:
    """The centroid of a cell of layer whose centroid projects inside the view."""
    mesh_points = np.asarray(win.scene.meshes[layer].points)
    cells = win.scene.layers[layer].cells
    width, height = win.scene.plotter.renderer.GetSize()
    for row in np.linspace(0, len(cells) - 1, 50).astype(int):
        centre = mesh_points[cells[row]].mean(axis=0)
        x, y = display_point(win, centre)
        if 10 < x < width - 10 and 10 < y < height - 10:
            return centre
    raise AssertionError(f"no cell of {layer} in view")


def assert_shows_the_table(win, vertices_drawn: set[int] | None = None) -> None:
    """The dock's item is a table row; every field shown equals the table's value."""
    ac, alpha = win.model.dataset.ac, win.model.alpha
    panel = win.inspect_panel
    item = panel.item
    assert item is not None
    np.testing.assert_array_equal(ac.simplices(item.k)[item.row], item.vertices)
    iv = ac.intervals(item.k)[item.row]
    for column, name in enumerate(("enter", "regular", "interior")):
        assert panel.fields[name].text() == alpha_text(iv[column])
    expected = CLASSES[int(ac.classify(alpha, item.k)[item.row])]
    assert f"<b>{expected}</b>" in panel.class_text()
    assert panel.fields["vertices"].text() == ", ".join(f"{int(v):,}" for v in item.vertices)
    coords = panel.fields["coordinates"].text().split("<br>")
    for line, xyz in zip(coords, ac.to_ambient(ac.points[item.vertices]), strict=True):
        np.testing.assert_allclose([float(c) for c in line.split(", ")], xyz, rtol=1e-5)
    if vertices_drawn is not None:
        assert set(item.vertices.tolist()) <= vertices_drawn


@pytest.mark.parametrize("layer", ["surface", "interior"])
def test_a_click_shows_the_picked_simplex_from_the_table(opened, qtbot, layer) -> None:
    """Clicking a drawn cell fills the dock with its row of the table; the picked point lies
    on that simplex (so the cell id was mapped to the right vertices)."""
    win = opened
    target = visible_target(win, surface(win) if layer == "surface" else layer)
    click_view(win, qtbot, *display_point(win, target))
    item = win.inspect_panel.item
    assert item is not None and win.inspector.dock.isVisible()
    assert_shows_the_table(win)
    picked = np.asarray(win.inspector.picker.picker.GetPickPosition())
    corners = np.asarray(win.scene.meshes["points"].points)[item.vertices]
    lo, hi = corners.min(axis=0), corners.max(axis=0)
    # lines and points are picked within the picker's tolerance (a fraction of the window)
    slack = 0.01 * np.ptp(np.asarray(win.scene.meshes["points"].points), axis=0).max()
    assert np.all(picked >= lo - slack) and np.all(picked <= hi + slack)
    assert item.k >= 1  # a triangle or cell is hit here (points/edges: the next test)


def test_every_layer_cell_maps_to_its_table_row(opened) -> None:
    """The same mapping the click uses, for cells of every shown layer."""
    win = opened
    for name in win.scene.layers:
        win.layers_panel._edit(name, visible=True)
    ac = win.model.dataset.ac
    for layer in win.scene.layers.values():
        for cell in np.linspace(0, len(layer.cells) - 1, 5).astype(int) if len(layer.cells) else []:
            win.inspector.inspect_vertices(layer.cells[cell])
            item = win.inspect_panel.item
            assert sorted(item.vertices.tolist()) == sorted(np.asarray(layer.cells[cell]).tolist())
            assert item.k == layer.cells.shape[1] - 1
            assert_shows_the_table(win)
            assert item.class_index(win.model.alpha) == ac.classify(win.model.alpha,
                                                                    item.k)[item.row]


def test_class_follows_the_slider_and_clear_removes_the_highlight(opened, qtbot) -> None:
    """After a pick, alpha steps update the class shown; Clear removes the overlay."""
    win = opened
    layer = win.scene.layers[surface(win)]
    win.inspector.inspect_vertices(layer.cells[len(layer.cells) // 2])
    assert "inspect_simplex" in win.scene.plotter.actors
    for index in (0, win.model.index // 2, win.model.hull_index()):
        win.model.set_index(index)
        assert_shows_the_table(win)
    win.inspect_panel.clear_button.click()
    assert win.inspect_panel.item is None
    assert "inspect_simplex" not in win.scene.plotter.actors


def test_spoon_is_drawn_through_the_simplex(opened, qtbot) -> None:
    """Ticking "Show its spoon" draws a sphere (circle in 2D) of radius enter around the
    simplex's spoon centre; unticking removes it."""
    from core.query.spheres import simplex_sphere

    win = opened
    layer = win.scene.layers[surface(win)]
    win.inspector.inspect_vertices(layer.cells[0])
    item = win.inspect_panel.item
    win.inspect_panel.spoon.setChecked(True)
    actor = win.scene.plotter.actors["inspect_spoon"]
    centre, radius = simplex_sphere(win.model.dataset.ac, item.k, item.row)
    assert radius == pytest.approx(item.intervals[0])
    bounds = np.asarray(actor.GetBounds()).reshape(-1, 2)
    np.testing.assert_allclose(bounds[: len(centre)].mean(axis=1), centre, atol=1e-3 * radius)
    np.testing.assert_allclose(np.diff(bounds[: len(centre)], axis=1).ravel(), 2 * radius,
                               rtol=0.02)
    win.inspect_panel.spoon.setChecked(False)
    assert "inspect_spoon" not in win.scene.plotter.actors


def test_a_drag_does_not_pick(opened, qtbot) -> None:
    """Press, move and release (a rotation) inspects nothing."""
    win = opened
    x, y = display_point(win, visible_target(win, surface(win)))
    widget = win.scene.plotter
    start = QPoint(round(x), round(widget.height() - 1 - y))
    qtbot.mousePress(widget, Qt.MouseButton.LeftButton, pos=start)
    qtbot.mouseMove(widget, start + QPoint(40, 25))
    qtbot.mouseRelease(widget, Qt.MouseButton.LeftButton, pos=start + QPoint(40, 25))
    qtbot.wait(20)
    assert win.inspect_panel.item is None



"""The clipping plane: it cuts what is drawn (rendering only, no geometry work), follows a new
dataset, and turns off cleanly."""

from __future__ import annotations

import numpy as np
import pytest
from conftest import open_and_wait

from app.palette import BACKGROUND


def ball(n: int = 1500, seed: int = 4) -> np.ndarray:
    """(n, 3) points filling a ball: a solid with interior cells."""
    rng = np.random.default_rng(seed)
    directions = rng.normal(size=(n, 3))
    directions /= np.linalg.norm(directions, axis=1)[:, None]
    return directions * rng.uniform(0, 1, (n, 1)) ** (1 / 3)


@pytest.fixture
def opened(window, qtbot, tmp_path):
    """The window on a solid ball, interior cells shown."""
    path = tmp_path / "ball.npy"
    np.save(path, ball())
    open_and_wait(qtbot, window, path)
    window.layers_panel._edit("interior", visible=True, opacity=1.0)
    return window


def shot(win, qtbot) -> np.ndarray:
    """The view as an (h, w, 3) image."""
    win.scene.plotter.render()
    qtbot.wait(20)
    return win.scene.plotter.screenshot(return_img=True)[..., :3]


def covered(image: np.ndarray) -> float:
    """Fraction of pixels that are not background."""
    background = np.array([int(BACKGROUND[i:i + 2], 16) for i in (1, 3, 5)])
    return float((np.abs(image.astype(int) - background).sum(axis=2) > 30).mean())


def test_clipping_cuts_the_picture_and_keeps_the_geometry(opened, qtbot) -> None:
    """View → Clipping plane attaches one plane to every layer; half the ball disappears (the
    interior cells show in the cut); the layers' connectivity is untouched; off restores."""
    win = opened
    before = {name: layer.cells for name, layer in win.scene.layers.items()}
    plain = shot(win, qtbot)
    win.menus["clip"].trigger()
    assert win.scene.clipper.enabled and win.menus["clip"].isChecked()
    for layer in win.scene.layers.values():
        planes = layer.actor.mapper.GetClippingPlanes()
        assert planes is not None and planes.GetNumberOfItems() == 1
    assert len(win.scene.plotter.widgets.plane_widgets) == 1  # the handle that moves the plane
    win.scene.plotter.widgets.plane_widgets[0].Off()  # measure what the layers draw, not the handle
    cut = shot(win, qtbot)
    assert covered(cut) < 0.8 * covered(plain)
    assert {name: layer.cells for name, layer in win.scene.layers.items()} == before
    win.scene.clipper.set_plane(np.zeros(3), (0.0, 0.0, 1.0))
    turned = shot(win, qtbot)
    assert np.abs(turned.astype(int) - cut.astype(int)).sum() > 0
    win.menus["clip"].trigger()
    assert not win.scene.clipper.enabled and not win.scene.plotter.widgets.plane_widgets
    restored = shot(win, qtbot)
    assert covered(restored) == pytest.approx(covered(plain), abs=0.01)


def test_clipping_survives_a_slider_step_and_a_new_dataset(opened, qtbot, tmp_path) -> None:
    """With the plane on, a slider step keeps it, and a newly opened file's layers get it."""
    win = opened
    win.menus["clip"].trigger()
    win.model.set_index(win.model.index - 10)
    assert win.scene.layers["surface"].actor.mapper.GetClippingPlanes().GetNumberOfItems() == 1
    path = tmp_path / "other.npy"
    np.save(path, ball(800, seed=8) * 3.0)
    open_and_wait(qtbot, win, path)
    for layer in win.scene.layers.values():
        assert layer.actor.mapper.GetClippingPlanes().GetNumberOfItems() == 1
    origin = np.asarray(win.scene.clipper.plane.GetOrigin())
    assert np.linalg.norm(origin) < 0.5  # placed through the new data's centre

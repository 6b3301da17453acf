"""The first window: opens on the bundled sample, shows exactly its points, renders non-blank."""

from __future__ import annotations

import numpy as np
import pytest
from conftest import image_contrast, open_and_wait
from plyfile import PlyData

from app.resources import SAMPLE_PATH

MIN_CONTRAST = 10.0


def sample_points() -> np.ndarray:
    """(n, 3) float64 points of assets/sample.ply, read independently of the app."""
    vertex = PlyData.read(str(SAMPLE_PATH))["vertex"]
    return np.column_stack([vertex[axis] for axis in "xyz"]).astype(np.float64)


def test_sample_is_small_and_sizeable() -> None:
    """The bundled sample stays well under 1 MB and holds 15-25k points."""
    assert SAMPLE_PATH.stat().st_size < 500_000
    assert 15_000 <= len(sample_points()) <= 25_000


@pytest.fixture
def sample_window(window, qtbot):
    """The window after opening the bundled sample (waits for the build)."""
    open_and_wait(qtbot, window, SAMPLE_PATH)
    return window


def test_window_shows_the_sample_points(sample_window) -> None:
    """The points layer holds exactly the sample's points (mapped back to file order)."""
    mesh = sample_window.scene.meshes["points"]
    ac = sample_window.model.dataset.ac
    expected = sample_points()
    assert mesh.n_points == len(ac.points) == len(expected)
    assert np.array_equal(np.asarray(mesh.points)[ac.input_index], expected)
    assert mesh.n_verts == len(expected)


def test_window_screenshot_is_not_blank(sample_window, qtbot) -> None:
    """A screenshot of the window's view has contrast (a black or empty frame fails)."""
    window = sample_window
    window.scene.plotter.interactor.update()
    qtbot.wait(50)
    image = window.scene.plotter.screenshot(return_img=True)
    assert image.shape[0] > 100 and image.shape[1] > 100
    assert image_contrast(image) > MIN_CONTRAST


def test_contrast_measure_rejects_a_black_frame() -> None:
    """The contrast check is able to fail: a uniform frame scores zero."""
    assert image_contrast(np.zeros((64, 64, 3), dtype=np.uint8)) < MIN_CONTRAST


def test_first_frame_is_drawn_at_the_final_view_size(window, qtbot) -> None:
    """The docks take the widths a dataset's panels need before its first frame: the view
    has its final size once the load is handled, so the shape is not drawn again by a
    resize afterwards (a whole extra frame at a million points)."""
    view = window.centralWidget()
    seen = []
    window.loader.finished.connect(lambda *_: seen.append(view.size()))  # after the window's
    with qtbot.waitSignal(window.model.datasetChanged, timeout=120_000):
        window.open_path(SAMPLE_PATH)
    qtbot.wait(500)
    assert seen == [view.size()]

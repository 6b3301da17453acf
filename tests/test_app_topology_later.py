"""The slider is live before the topology: the docks fill in when it arrives."""

from __future__ import annotations

import threading

import numpy as np
import pytest
from conftest import BUILD_TIMEOUT_MS, wait_for_topology
from PySide6.QtCore import Qt

from app.alpha_panel import OPTIMAL_TEXT, OPTIMAL_WAIT_TEXT
from app.signatures_dock import COMPUTING

RELEASE_TIMEOUT_S = 60


def ring(n: int, seed: int) -> np.ndarray:
    """(n, 3) a noisy solid ring: one component and one tunnel at its opening alpha."""
    rng = np.random.default_rng(seed)
    angle = rng.uniform(0, 2 * np.pi, n)
    return (np.column_stack([np.cos(angle), np.sin(angle), np.zeros(n)])
            + rng.normal(scale=0.15, size=(n, 3)))


@pytest.fixture(autouse=True)
def private_cache(tmp_path, monkeypatch):
    """Each test starts with an empty table cache: its files are built, not loaded."""
    monkeypatch.setenv("ALPHASCOOP_CACHE_DIR", str(tmp_path / "cache"))


@pytest.fixture
def held(monkeypatch):
    """Topology passes wait until the test sets the returned event (the table does not)."""
    import app.worker

    release = threading.Event()
    real = app.worker.with_topology

    def held_with_topology(dataset, check=None):
        assert release.wait(RELEASE_TIMEOUT_S), "the test never released the topology"
        return real(dataset, check)

    monkeypatch.setattr(app.worker, "with_topology", held_with_topology)
    yield release
    release.set()  # never leave a worker thread waiting


@pytest.fixture
def points_path(tmp_path):
    """A fresh (never cached) point file of 1500 ring points."""
    path = tmp_path / "ring.npy"
    np.save(path, ring(1500, seed=21))
    return path


def open_table(qtbot, window, path) -> None:
    """Open path and wait only for the table (the slider), not for the topology."""
    with qtbot.waitSignal(window.model.datasetChanged, timeout=BUILD_TIMEOUT_MS):
        window.open_path(path)


def press(qtbot, window, key) -> None:
    """A key on the focused slider, then let the coalescing timer run."""
    qtbot.keyClick(window.alpha_panel.slider, key)
    qtbot.wait(20)


def test_slider_is_usable_before_the_signatures_exist(window, qtbot, held, points_path):
    open_table(qtbot, window, points_path)
    ds, panel = window.model.dataset, window.alpha_panel
    assert not ds.has_topology and ds.signatures is None
    assert not panel.optimal.isEnabled() and panel.optimal.text() == OPTIMAL_WAIT_TEXT
    assert not any(ax.get_visible() for ax in window.signatures_panel.figure.axes)
    assert window.signatures_panel.computing.get_visible()
    assert window.signatures_panel.computing.get_text() == COMPUTING
    assert "computing" in window.info_panel.shape.text()
    assert "built in" in window.status.text() and "topology: computing" in window.status.text()
    start = window.model.index
    cells_before = len(window.model.shape.cells)
    for _ in range(5):
        press(qtbot, window, Qt.Key.Key_Right)
    assert window.model.index == start + 5
    shape = window.model.shape
    assert len(shape.cells) >= cells_before
    np.testing.assert_array_equal(shape.cells, ds.ac.shape(window.model.alpha).cells)
    window.menus["optimal"].trigger()  # Ctrl+1 before the optimal alpha is known: no move
    assert window.model.index == start + 5


def test_the_docks_fill_in_and_a_touched_slider_stays(window, qtbot, held, points_path):
    open_table(qtbot, window, points_path)
    press(qtbot, window, Qt.Key.Key_Left)
    moved_to = window.model.index
    with qtbot.waitSignal(window.model.topologyChanged, timeout=BUILD_TIMEOUT_MS):
        held.set()
    ds, panel = window.model.dataset, window.alpha_panel
    assert ds.has_topology and ds.signatures is not None and ds.optimal_alpha is not None
    assert window.model.index == moved_to  # the user's choice wins over the opening alpha
    assert panel.optimal.isEnabled() and panel.optimal.text() == OPTIMAL_TEXT
    assert all(ax.get_visible() for ax in window.signatures_panel.figure.axes)
    assert not window.signatures_panel.computing.get_visible()
    assert "component" in window.info_panel.shape.text()
    assert "topology in" in window.status.text()
    qtbot.mouseClick(panel.optimal, Qt.MouseButton.LeftButton)
    assert window.model.index == window.model.optimal_index() != moved_to


def test_an_untouched_slider_moves_to_the_opening_alpha(window, qtbot, held, points_path,
                                                         monkeypatch):
    """When the quick choice differs from the opening alpha (here forced: the hull), the view
    moves there once the topology is known, as long as nobody touched the slider."""
    monkeypatch.setattr("app.dataset.quick_alpha", lambda ac: float(ac.spectrum()[-1]))
    open_table(qtbot, window, points_path)
    assert window.model.index == window.model.hull_index()
    with qtbot.waitSignal(window.model.topologyChanged, timeout=BUILD_TIMEOUT_MS):
        held.set()
    ds = window.model.dataset
    assert ds.default_alpha == ds.ac.default_alpha()
    assert window.model.index == window.model.default_index() < window.model.hull_index()
    assert not window.model.history.can_back()  # the move is not a step to undo


def test_a_new_file_drops_the_old_topology(window, qtbot, held, tmp_path):
    first, second = tmp_path / "first.npy", tmp_path / "second.npy"
    np.save(first, ring(1200, seed=22))
    np.save(second, ring(900, seed=23))
    ready: list[int] = []
    window.topology.finished.connect(lambda request, _ds: ready.append(request))
    open_table(qtbot, window, first)
    old = window.topology.current
    open_table(qtbot, window, second)
    held.set()
    wait_for_topology(qtbot, window)
    window.topology.wait()
    qtbot.wait(20)
    assert ready == [window.topology.current] and old not in ready
    assert window.model.dataset.path == second and window.model.dataset.has_topology


def test_the_model_ignores_another_datasets_topology(window, qtbot, held, tmp_path):
    from dataclasses import replace

    first, second = tmp_path / "a.npy", tmp_path / "b.npy"
    np.save(first, ring(700, seed=24))
    np.save(second, ring(600, seed=25))
    open_table(qtbot, window, first)
    stale = window.model.dataset
    open_table(qtbot, window, second)
    held.set()
    wait_for_topology(qtbot, window)
    current = window.model.dataset
    assert not window.model.set_topology(replace(stale, signatures=current.signatures))
    assert window.model.dataset is current


def test_reopening_comes_complete_from_the_cache(window, qtbot, points_path):
    open_table(qtbot, window, points_path)
    wait_for_topology(qtbot, window)
    window.topology.wait()  # the entry is rewritten with the signatures
    open_table(qtbot, window, points_path)
    ds = window.model.dataset
    assert ds.source == "cache" and ds.has_topology  # no second pass, no waiting dock
    assert "loaded from cache in" in window.status.text()
    assert "topology from cache" in window.status.text()


def test_an_older_files_topology_failure_is_not_said_over_a_complete_one(
        window, qtbot, monkeypatch, tmp_path, points_path):
    """A topology pass that fails after a file that came complete (from the cache: nothing
    superseded the pass) is shown says nothing over that file."""
    import app.worker
    from core.errors import InputError

    open_table(qtbot, window, points_path)
    wait_for_topology(qtbot, window)  # its table is cached with its topology now
    release = threading.Event()

    def failing(dataset, check=None):
        assert release.wait(RELEASE_TIMEOUT_S), "the test never released the topology"
        raise InputError("the forests went wrong")

    monkeypatch.setattr(app.worker, "with_topology", failing)
    other = tmp_path / "other.npy"
    np.save(other, ring(800, seed=5))
    try:
        open_table(qtbot, window, other)
        open_table(qtbot, window, points_path)
        assert window.model.dataset.has_topology
    finally:
        release.set()
    qtbot.waitUntil(lambda: not window.topology.is_busy(), timeout=BUILD_TIMEOUT_MS)
    qtbot.wait(50)
    assert window.model.dataset.path == points_path
    assert "went wrong" not in window.status.text()

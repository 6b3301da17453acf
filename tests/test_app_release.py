"""The window holds one table at a time and the topology comes from its own process.

A new open releases the shown dataset once the new file is read (before its table is built or
loaded); a cancelled or failed load re-opens the released file from the table cache. Big
datasets get their topology from a topology process; the docks fill in as with the pass in
a thread.
"""

from __future__ import annotations

import gc
import multiprocessing
import threading
import weakref

import numpy as np
import pytest
from conftest import BUILD_TIMEOUT_MS, open_and_wait

import app.dataset
from app import topology_process
from core import AlphaComplex

HOLD_TIMEOUT_S = 60


@pytest.fixture(autouse=True)
def private_cache(tmp_path, monkeypatch):
    """Each test starts with an empty table cache."""
    monkeypatch.setenv("ALPHASCOOP_CACHE_DIR", str(tmp_path / "cache"))


def blobs(n: int, seed: int) -> np.ndarray:
    """(n, 3) two noisy blobs: a small solid set."""
    rng = np.random.default_rng(seed)
    return np.concatenate([rng.normal(size=(n // 2, 3)), rng.normal(size=(n - n // 2, 3)) + 4])


@pytest.fixture
def files(tmp_path):
    """A shown file, a second and a third one and a file of collinear points (no complex)."""
    paths = {name: tmp_path / f"{name}.npy" for name in ("shown", "next", "third", "line")}
    np.save(paths["shown"], blobs(900, seed=1))
    np.save(paths["next"], blobs(700, seed=2))
    np.save(paths["third"], blobs(800, seed=3))
    line = np.arange(50.0)
    np.save(paths["line"], np.column_stack([line, 2 * line, 3 * line]))
    return paths


@pytest.fixture
def held(monkeypatch):
    """Loads stop before their table (after the file was read) until the test sets the
    returned event; Cancel still stops them (they keep reporting progress)."""
    go, real = threading.Event(), app.dataset.obtain

    def held_obtain(points, **kwargs):
        progress = kwargs["progress"]
        for _ in range(int(HOLD_TIMEOUT_S / 0.02)):
            if go.wait(0.02):
                return real(points, **kwargs)
            progress(0.0, "held")  # raises Cancelled once the load is cancelled
        raise AssertionError("the test never let the load go on")

    monkeypatch.setattr(app.dataset, "obtain", held_obtain)
    yield go
    go.set()


def test_a_new_load_releases_the_shown_dataset_and_cancel_brings_it_back(
        window, qtbot, files, held):
    held.set()
    open_and_wait(qtbot, window, files["shown"])
    shown = weakref.ref(window.model.dataset)
    held.clear()
    with qtbot.waitSignal(window.model.datasetReleased, timeout=BUILD_TIMEOUT_MS):
        window.open_path(files["next"])
    gc.collect()
    assert shown() is None and window.model.dataset is None  # one table at a time
    assert window.scene.layers == {} and window.scene.shape is None
    assert "shown.npy was closed" in window.status.text()
    assert not window.alpha_panel.isEnabled()
    held.set()  # the re-open below reads the cache
    with qtbot.waitSignal(window.model.datasetChanged, timeout=BUILD_TIMEOUT_MS):
        window.loader.cancel()
    assert window.model.dataset.path == files["shown"]
    assert window.model.dataset.source == "cache"
    assert window.windowTitle() == "Alpha Scoop - shown.npy"


def test_a_failed_build_brings_the_released_file_back(window, qtbot, files, monkeypatch):
    from PySide6.QtWidgets import QMessageBox

    warnings: list[str] = []
    monkeypatch.setattr(QMessageBox, "warning", lambda *args: warnings.append(args[2]))
    open_and_wait(qtbot, window, files["shown"])
    with qtbot.waitSignal(window.loader.failed, timeout=BUILD_TIMEOUT_MS):
        window.open_path(files["line"])
    assert len(warnings) == 1 and "Traceback" not in warnings[0]
    qtbot.waitUntil(lambda: window.model.dataset is not None, timeout=BUILD_TIMEOUT_MS)
    assert window.model.dataset.path == files["shown"]


def test_a_file_that_cannot_be_read_keeps_the_shown_dataset(window, qtbot, files, tmp_path,
                                                            monkeypatch):
    from PySide6.QtWidgets import QMessageBox

    monkeypatch.setattr(QMessageBox, "warning", lambda *args: None)
    open_and_wait(qtbot, window, files["shown"])
    shown = window.model.dataset
    released: list[bool] = []
    window.model.datasetReleased.connect(lambda: released.append(True))
    (tmp_path / "bad.xyz").write_text("not numbers\n")
    with qtbot.waitSignal(window.loader.failed, timeout=BUILD_TIMEOUT_MS):
        window.open_path(tmp_path / "bad.xyz")
    assert window.model.dataset is shown and released == []


def test_the_topology_process_fills_the_docks(window, qtbot, files, monkeypatch):
    monkeypatch.setattr(topology_process, "IN_THREAD_BELOW", 0)
    with qtbot.waitSignal(window.model.topologyChanged, timeout=BUILD_TIMEOUT_MS):
        window.open_path(files["shown"])
    ds = window.model.dataset
    here = AlphaComplex.from_points(np.load(files["shown"]))
    np.testing.assert_array_equal(ds.signatures.betti, here.signatures().betti)
    np.testing.assert_array_equal(ds.persistence.diagram(2), here.persistence().diagram(2))
    assert ds.optimal_alpha == here.optimal_alpha() and ds.default_alpha == here.default_alpha()
    assert ds.ac.has_signatures and ds.cursor is not None
    assert len(window.signatures_panel.figure.axes) == 4
    assert all(ax.get_visible() for ax in window.signatures_panel.figure.axes)
    assert not window.signatures_panel.computing.get_visible()
    assert "topology in" in window.status.text()
    window.topology.wait()  # the process then rewrites the cache entry, and ends
    qtbot.waitUntil(lambda: not multiprocessing.active_children(), timeout=BUILD_TIMEOUT_MS)
    window.alpha_panel.slider.setFocus()
    index = window.model.index
    window.model.set_index(index + 1)
    np.testing.assert_array_equal(window.model.shape.cells,
                                  here.shape(window.model.alpha).cells)


def test_a_cancelled_load_brings_the_released_file_back_at_the_users_alpha(
        window, qtbot, files, held):
    held.set()
    open_and_wait(qtbot, window, files["shown"])
    window.topology.wait()
    qtbot.waitUntil(lambda: window.model.dataset.has_topology, timeout=BUILD_TIMEOUT_MS)
    opening = window.model.index
    window.model.set_index(opening - 7)  # the user drags away from the opening alpha
    chosen = window.model.alpha
    held.clear()
    with qtbot.waitSignal(window.model.datasetReleased, timeout=BUILD_TIMEOUT_MS):
        window.open_path(files["next"])
    held.set()
    with qtbot.waitSignal(window.model.datasetChanged, timeout=BUILD_TIMEOUT_MS):
        window.loader.cancel()
    qtbot.waitUntil(lambda: not window.loader.is_busy(), timeout=BUILD_TIMEOUT_MS)
    assert window.model.dataset.path == files["shown"]
    assert window.model.index == opening - 7 and window.model.alpha == chosen


def _drag_then_cancel_an_open(window, qtbot, files, held) -> None:
    """Show `shown`, drag away from its opening alpha, start opening `next` and cancel it:
    the re-open of `shown` (held) is then running."""
    held.set()
    open_and_wait(qtbot, window, files["shown"])
    window.model.set_index(window.model.index - 7)
    held.clear()
    with qtbot.waitSignal(window.model.datasetReleased, timeout=BUILD_TIMEOUT_MS):
        window.open_path(files["next"])
    window.loader.cancel()
    qtbot.waitUntil(lambda: "re-opening" in window.status.text(), timeout=BUILD_TIMEOUT_MS)


def _open_third_at_its_own_alpha(window, qtbot, files, held, instead: str) -> None:
    """Let the builds go, open `third` and assert it opened at its own opening alpha, not
    at `instead`."""
    held.set()
    with qtbot.waitSignal(window.model.datasetChanged, timeout=BUILD_TIMEOUT_MS):
        window.open_path(files["third"])
    qtbot.waitUntil(lambda: not window.loader.is_busy(), timeout=BUILD_TIMEOUT_MS)
    assert not window.model.touched, f"the third file opened at {instead}"
    assert window.model.index == window.model.default_index()


def test_a_file_opened_during_the_reopen_opens_at_its_own_alpha(window, qtbot, files, held):
    _drag_then_cancel_an_open(window, qtbot, files, held)
    window.open_path(files["third"])  # supersedes the re-open of "shown"
    held.set()
    qtbot.waitUntil(lambda: window.model.dataset is not None
                    and window.model.dataset.path == files["third"], timeout=BUILD_TIMEOUT_MS)
    qtbot.waitUntil(lambda: not window.loader.is_busy(), timeout=BUILD_TIMEOUT_MS)
    assert not window.model.touched, "the third file opened at the first one's alpha"
    assert window.model.index == window.model.default_index()


def test_a_file_opened_after_a_cancelled_reopen_opens_at_its_own_alpha(
        window, qtbot, files, held):
    _drag_then_cancel_an_open(window, qtbot, files, held)
    with qtbot.waitSignal(window.loader.cancelled, timeout=BUILD_TIMEOUT_MS):
        window.loader.cancel()  # the user cancels the re-open too
    _open_third_at_its_own_alpha(window, qtbot, files, held, "the first one's alpha")


def test_a_start_alpha_of_a_cancelled_first_open_is_not_kept_for_the_next(
        window, qtbot, files, held):
    window.start_alpha = 0.05  # as `alphascoop FILE --alpha 0.05` starts the window
    with qtbot.waitSignal(window.loader.cancelled, timeout=BUILD_TIMEOUT_MS):
        window.open_path(files["next"])  # held: still building when cancelled
        window.loader.cancel()
    _open_third_at_its_own_alpha(window, qtbot, files, held, "the cancelled one's --alpha")


def test_a_start_alpha_is_not_given_to_a_file_that_superseded_its_open(
        window, qtbot, files, held):
    """`alphascoop FILE --alpha A`, then the user opens another file before FILE is built:
    that file opens at its own opening alpha, not at A (before, A went to whichever load
    finished first)."""
    window.start_alpha = 0.05
    window.open_path(files["next"])  # held: still building
    _open_third_at_its_own_alpha(window, qtbot, files, held, "the superseded one's --alpha")


def test_a_start_alpha_goes_to_its_own_open(window, qtbot, files, held):
    window.start_alpha = 0.05
    held.set()
    with qtbot.waitSignal(window.model.datasetChanged, timeout=BUILD_TIMEOUT_MS):
        window.open_path(files["next"])
    assert window.model.touched and window.model.alpha == pytest.approx(0.05, rel=0.05)


@pytest.mark.parametrize("error", [KeyboardInterrupt, SystemExit])
def test_a_load_stopped_by_a_base_exception_fails_and_brings_the_file_back(
        window, qtbot, files, monkeypatch, error):
    """A KeyboardInterrupt or SystemExit out of the load's code (not Cancel) used to end the
    runner's thread with no outcome: 'opening next.npy' stayed in the status bar, the
    released file never came back and no later open ran. Now it is a failed open."""
    from PySide6.QtWidgets import QMessageBox

    warnings: list[str] = []
    monkeypatch.setattr(QMessageBox, "warning", lambda *args: warnings.append(args[2]))
    monkeypatch.setattr(threading, "excepthook", lambda args: None)  # the thread's end
    open_and_wait(qtbot, window, files["shown"])
    real, calls = app.dataset.obtain, []

    def interrupted(points, **kwargs):  # the first load only: the re-open runs at once
        calls.append(points)
        if len(calls) == 1:
            raise error
        return real(points, **kwargs)

    monkeypatch.setattr(app.dataset, "obtain", interrupted)
    with qtbot.waitSignal(window.loader.failed, timeout=BUILD_TIMEOUT_MS):
        window.open_path(files["next"])
    assert warnings == [f"opening next.npy stopped: {error.__name__}"]
    qtbot.waitUntil(lambda: window.model.dataset is not None, timeout=BUILD_TIMEOUT_MS)
    assert window.model.dataset.path == files["shown"]
    assert not window.progress.isVisible() and not window.loader.is_busy()
    with qtbot.waitSignal(window.model.datasetChanged, timeout=BUILD_TIMEOUT_MS):
        window.open_path(files["third"])
    assert window.model.dataset.path == files["third"]

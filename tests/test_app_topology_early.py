"""The window starts the topology process as soon as it has the table the build process
handed over and its cursor, while the load still goes on: the topology arrives,
the entry gets the signatures for the next open, and a load cancelled, superseded or
failed after that start leaves no process, no scratch folder and no topology behind."""

from __future__ import annotations

import multiprocessing
import os
import signal
import tempfile
import threading
import time
from pathlib import Path

import numpy as np
import pytest
from conftest import BUILD_TIMEOUT_MS

import app.worker
from app import build_process, topology_process
from app.messages import OpeningFound
from app.topology_child import TopologyChild
from core import AlphaComplex
from core.cache import load_cached

HOLD_S = 60
TOPOLOGY_STARTED = "choosing alpha"  # the load's stage after the build runner returned
TABLE_LOADING = "loading the table"  # the build runner maps the handed table, makes the cursor


@pytest.fixture(autouse=True)
def in_children(tmp_path, monkeypatch):
    """An empty table cache; builds and topology passes of every size in their processes."""
    monkeypatch.setenv("ALPHASCOOP_CACHE_DIR", str(tmp_path / "cache"))
    monkeypatch.setattr(build_process, "IN_THREAD_BELOW", 0)
    monkeypatch.setattr(topology_process, "IN_THREAD_BELOW", 0)


@pytest.fixture
def started(monkeypatch) -> list[TopologyChild]:
    """The topology processes the load jobs start (early), in order."""
    made: list[TopologyChild] = []

    class Recorded(TopologyChild):
        def __init__(self, *args, **kwargs) -> None:
            super().__init__(*args, **kwargs)
            made.append(self)

    monkeypatch.setattr(app.worker, "TopologyChild", Recorded)
    return made


def blobs(n: int, seed: int) -> np.ndarray:
    """(n, 3) two noisy blobs."""
    rng = np.random.default_rng(seed)
    return np.concatenate([rng.normal(size=(n // 2, 3)), rng.normal(size=(n - n // 2, 3)) + 4])


@pytest.fixture
def files(tmp_path) -> dict[str, Path]:
    """Two point files."""
    paths = {name: tmp_path / f"{name}.npy" for name in ("first", "second")}
    np.save(paths["first"], blobs(2000, seed=1))
    np.save(paths["second"], blobs(1500, seed=2))
    return paths


def hold_first_load(monkeypatch, then, at: str = TOPOLOGY_STARTED) -> threading.Event:
    """The first load stops at the stage `at` (default: once its build runner returned, the
    topology process started) and calls then(runner) there; the returned event is set when
    it got there."""
    real, reached = app.worker.load_dataset, threading.Event()

    def load(path, progress, runner, **kwargs):
        def held(fraction: float, stage: str) -> None:
            if stage == at and not reached.is_set():
                reached.set()
                then(runner)
            progress(fraction, stage)

        return real(path, held, runner, **kwargs)

    monkeypatch.setattr(app.worker, "load_dataset", load)
    return reached


def freeze_the_entry_writer(monkeypatch) -> list[int]:
    """Stop (SIGSTOP) the build process as soon as it has handed its opening alpha over, so
    it is still writing the cache entry, frozen, whatever the machine's speed: it can only
    end if the window kills it. Returns the pids frozen."""
    real, frozen = build_process.run_in_child, []

    def run(work, args, progress, cancel, name, handed=None, finish=None):
        def freeze_then(message: object) -> None:
            if isinstance(message, OpeningFound):
                for child in multiprocessing.active_children():
                    if child.name == name:
                        os.kill(child.pid, signal.SIGSTOP)
                        frozen.append(child.pid)
            handed(message)

        return real(work, args, progress, cancel, name,
                    None if handed is None else freeze_then, finish)

    monkeypatch.setattr(build_process, "run_in_child", run)
    return frozen


def my_scratch() -> list[Path]:
    """This process's scratch folders in the temp dir."""
    return list(Path(tempfile.gettempdir()).glob(f"alphascoop-*-{os.getpid()}-*"))


def no_child_left(qtbot) -> None:
    """Wait until every child process has ended (a topology process rewrites the cache entry
    after the topology arrived) and check no scratch folder is left."""
    qtbot.waitUntil(lambda: not multiprocessing.active_children(), timeout=BUILD_TIMEOUT_MS)
    qtbot.waitUntil(lambda: not my_scratch(), timeout=BUILD_TIMEOUT_MS)


def test_the_topology_process_runs_before_the_dataset_arrives(window, qtbot, files, started):
    arrived: list[tuple[object, float]] = []
    window.model.datasetChanged.connect(
        lambda: arrived.append((window.model.dataset, time.perf_counter())))
    with qtbot.waitSignal(window.model.topologyChanged, timeout=BUILD_TIMEOUT_MS):
        window.open_path(files["first"])
    assert len(started) == 1 and arrived[0][0].topology_child is started[0]
    assert started[0].started < arrived[0][1]  # it ran before the dataset reached the window
    assert not arrived[0][0].has_topology
    ds, here = window.model.dataset, AlphaComplex.from_points(np.load(files["first"]))
    assert ds.topology_child is None
    for name in ("betti", "solid_components", "measure", "boundary_measure"):
        np.testing.assert_array_equal(getattr(ds.signatures, name),
                                      getattr(here.signatures(), name), err_msg=name)
    np.testing.assert_array_equal(ds.persistence.diagram(2), here.persistence().diagram(2))
    assert ds.optimal_alpha == here.optimal_alpha() and ds.default_alpha == here.default_alpha()
    assert "topology in" in window.status.text()
    no_child_left(qtbot)  # the rewrite of the entry follows the hand-over
    assert load_cached(np.load(files["first"])).has_signatures
    with qtbot.waitSignal(window.model.datasetChanged, timeout=BUILD_TIMEOUT_MS):
        window.open_path(files["first"])  # a re-open: the table and topology from the cache
    assert window.model.dataset.has_topology and window.model.dataset.from_cache
    assert len(started) == 1 and "topology from cache" in window.status.text()


def test_cancel_while_the_window_still_loads_stops_the_topology_process(
        window, qtbot, files, started, monkeypatch):
    reached = hold_first_load(monkeypatch, lambda runner: runner.cancel.wait(HOLD_S))
    frozen = freeze_the_entry_writer(monkeypatch)
    window.open_path(files["first"])
    qtbot.waitUntil(reached.is_set, timeout=BUILD_TIMEOUT_MS)
    assert len(started) == 1 and len(frozen) == 1
    with qtbot.waitSignal(window.loader.cancelled, timeout=BUILD_TIMEOUT_MS):
        window.loader.cancel()
    # the load job stopped its topology process and its build process (left writing the
    # cache entry) before it reported: nothing left at once
    assert multiprocessing.active_children() == [] and my_scratch() == []
    assert started[0].wait(0) and started[0].is_set()
    assert window.model.dataset is None
    window.topology.wait()
    assert window.model.dataset is None and not window.topology.is_busy()


def test_no_topology_process_before_the_cursor_and_none_after_a_cancel_there(
        window, qtbot, files, started, monkeypatch):
    """The topology process waits for the window's table and cursor (it would compete with
    them for the cores); cancelled once the table is loaded and the cursor made, but before
    that start, none starts at all."""
    seen: list[int] = []
    runners: list = []
    real_load = build_process._load_handed

    def then(runner) -> None:
        seen.append(len(started))  # the window is about to load the table
        runners.append(runner)

    def load_then_cancel(*args, **kwargs):
        taken = real_load(*args, **kwargs)
        seen.append(len(started))  # loaded, cursor made: still none
        runners[0].cancel.set()
        return taken

    hold_first_load(monkeypatch, then, at=TABLE_LOADING)
    monkeypatch.setattr(build_process, "_load_handed", load_then_cancel)
    with qtbot.waitSignal(window.loader.cancelled, timeout=BUILD_TIMEOUT_MS):
        window.open_path(files["first"])
    assert seen == [0, 0] and started == []
    no_child_left(qtbot)
    assert window.model.dataset is None


def test_a_superseded_load_stops_its_topology_process(window, qtbot, files, started,
                                                      monkeypatch):
    reached = hold_first_load(monkeypatch, lambda runner: runner.cancel.wait(HOLD_S))
    window.open_path(files["first"])
    qtbot.waitUntil(reached.is_set, timeout=BUILD_TIMEOUT_MS)
    with qtbot.waitSignal(window.model.topologyChanged, timeout=BUILD_TIMEOUT_MS):
        window.open_path(files["second"])  # supersedes the held load
    assert started[0].wait(0) and started[0].is_set()  # the first load's process: stopped
    assert len(started) == 2 and window.model.dataset.path == files["second"]
    here = AlphaComplex.from_points(np.load(files["second"]))
    np.testing.assert_array_equal(window.model.dataset.signatures.betti,
                                  here.signatures().betti)
    no_child_left(qtbot)


def test_a_load_that_fails_after_the_start_stops_the_topology_process(
        window, qtbot, files, started, monkeypatch):
    from PySide6.QtWidgets import QMessageBox

    monkeypatch.setattr(QMessageBox, "warning", lambda *args: None)

    def fail(_runner) -> None:
        raise MemoryError("no room for the table")

    hold_first_load(monkeypatch, fail)
    frozen = freeze_the_entry_writer(monkeypatch)
    with qtbot.waitSignal(window.loader.failed, timeout=BUILD_TIMEOUT_MS):
        window.open_path(files["first"])
    # the build process left writing the cache entry was killed and joined before `failed`
    # (it does not end by itself: it is frozen), its topology process too
    assert len(frozen) == 1
    assert multiprocessing.active_children() == [] and my_scratch() == []
    assert len(started) == 1 and started[0].wait(0)
    assert window.model.dataset is None and not window.topology.is_busy()

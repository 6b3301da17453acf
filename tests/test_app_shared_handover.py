"""The build process hands its table over in shared memory (app.shared_folder, core.storage.mapped):
before the cache entry is written, mapped by the window and the topology process, gone from
/dev/shm once both mapped it (or on cancel, failure, a killed window), a file hand-over when
shared memory is missing or too small, and the entry ends up whole, with the signatures."""

from __future__ import annotations

import fcntl
import gc
import multiprocessing
import os
import subprocess
import sys
import tempfile
import threading
import time
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from app import build_process, child_process
from app.messages import BuildJob, OpeningFound, TableHandedOver, TopologyJob
from app.shared_folder import SharedFolder, SharedTable
from app.topology_child import TopologyChild
from app.topology_process import HANDED_OVER, topology_in_child
from core import AlphaComplex
from core.cache import entry_path, read_entry
from core.errors import AlphaScoopError, Cancelled, FileFormatError
from core.modes.alpha_modes import Mode
from core.obtain import obtain
from core.storage import mapped
from core.topology.opening import opening_alpha_of

ROOT = Path(__file__).resolve().parents[1]
pytestmark = pytest.mark.skipif(not child_process.SHARED_ROOT.is_dir(), reason="no /dev/shm")


@pytest.fixture(autouse=True)
def in_process(monkeypatch, tmp_path):
    """Every build goes to a child process; a private cache folder."""
    monkeypatch.setattr(build_process, "IN_THREAD_BELOW", 0)
    monkeypatch.setenv("ALPHASCOOP_CACHE_DIR", str(tmp_path / "cache"))


@pytest.fixture(autouse=True)
def no_process_left():
    """A build process left to write its entry (the runner returned) ends before the next
    test counts processes."""
    yield
    assert wait_until(lambda: not multiprocessing.active_children())


def never(*_args) -> None:
    """A progress callback that ignores its reports."""


def my_shared() -> list[Path]:
    """This process's shared folders in /dev/shm."""
    return list(child_process.SHARED_ROOT.glob(f"alphascoop-shared-{os.getpid()}-*"))


def my_scratch() -> list[Path]:
    """This process's scratch folders in the temp dir."""
    return list(Path(tempfile.gettempdir()).glob(f"alphascoop-*-{os.getpid()}-*"))


def mapped_here(folder: Path) -> list[str]:
    """The lines of this process's memory map that map a file of folder."""
    return [line for line in Path("/proc/self/maps").read_text().splitlines()
            if str(folder) in line]


def run_body(tmp_path: Path, points: np.ndarray, shared: Path | None,
             save_to: Path | None) -> tuple[list[object], list[bool]]:
    """build_in_child run here: what it handed over, and whether the entry existed then."""
    np.save(tmp_path / "points.npy", points)
    job = BuildJob(Mode(), False, None if save_to is None else str(save_to), None,
                   None if shared is None else str(shared))
    handed: list[object] = []
    entry_then: list[bool] = []

    def hand_over(message: object) -> None:
        handed.append(message)
        entry_then.append(save_to is not None and save_to.exists())

    build_process.build_in_child(str(tmp_path / "points.npy"), str(tmp_path / "table.npz"),
                                 job, never, hand_over)
    return handed, entry_then


def test_the_table_is_handed_over_in_shared_memory_before_the_entry_is_written(tmp_path):
    points = np.random.default_rng(0).random((3000, 3))
    shared, entry = tmp_path / "shared", tmp_path / "cache" / "entry.npz"
    shared.mkdir()
    handed, entry_then = run_body(tmp_path, points, shared, entry)
    assert [type(h) for h in handed] == [TableHandedOver, OpeningFound]  # the table, then
    assert handed[0].mapped and entry_then == [False, False]  # the opening, before the entry
    built = AlphaComplex.from_points(points)
    assert handed[1] == OpeningFound(opening_alpha_of(built.index, built.points))
    assert handed[0].table == str(shared)
    here = AlphaComplex.from_points(points)
    got = AlphaComplex.load(shared, verify=False)
    for k in range(4):
        assert got.simplices(k).tobytes() == here.simplices(k).tobytes()
        assert got.intervals(k).tobytes() == here.intervals(k).tobytes()
    assert AlphaComplex.load(entry).intervals(3).tobytes() == here.intervals(3).tobytes()
    orders = mapped.map_arrays(handed[0].orders)
    assert not orders["regular"].flags.writeable
    assert orders["spectrum"].tobytes() == here.spectrum().tobytes()  # found beside


@pytest.mark.parametrize("shared", [True, False])
def test_the_window_takes_the_spectrum_its_child_found(tmp_path, shared, monkeypatch):
    """The handed table's index knows its spectrum (mapped, or from the orders' file), the
    same as a sort here; the window does not sort the table's values again."""
    if not shared:
        monkeypatch.setattr(child_process, "SHARED_ROOT", tmp_path / "no-shm")
    points = np.random.default_rng(5).random((3000, 3))
    runner = build_process.ChildRunner(threading.Event())
    monkeypatch.setattr(build_process, "IN_THREAD_BELOW", 0)
    ac = obtain(points, runner=runner, use_cache=False).complex
    assert ac.index.known_spectrum is not None
    assert ac.spectrum().tobytes() == AlphaComplex.from_points(points).spectrum().tobytes()
    assert runner.handed_over(ac).cursor is not None


def test_a_handed_spectrum_that_does_not_fit_the_table_is_refused(tmp_path):
    here = AlphaComplex.from_points(np.random.default_rng(6).random((500, 3)))
    here.save(tmp_path / "t.npz")
    good = here.spectrum()
    assert AlphaComplex.load(tmp_path / "t.npz", spectrum=good).index.known_spectrum is good
    for bad in (good[:-1], good.astype(np.float32), good.reshape(1, -1)):
        with pytest.raises(FileFormatError):
            AlphaComplex.load(tmp_path / "t.npz", verify=False, spectrum=bad)


def test_too_little_shared_memory_hands_the_entry_over_as_before(tmp_path, monkeypatch):
    """Forced fallback: /dev/shm too small for the table: nothing is left in it, and the
    table is handed over as the cache entry, written first."""
    monkeypatch.setattr(mapped, "ROOM_MARGIN", 2**62)
    points = np.random.default_rng(1).random((3000, 3))
    shared, entry = tmp_path / "shared", tmp_path / "cache" / "entry.npz"
    shared.mkdir()
    handed, entry_then = run_body(tmp_path, points, shared, entry)
    assert [h.mapped for h in handed] == [False] and entry_then == [True]
    assert handed[0].table == str(entry) and list(shared.iterdir()) == []


def test_without_shared_memory_the_runner_hands_a_file_over(monkeypatch, tmp_path):
    monkeypatch.setattr(child_process, "SHARED_ROOT", tmp_path / "no-shm")
    seen: list[SharedTable | None] = []
    points = np.random.default_rng(2).random((3000, 3))
    runner = build_process.ChildRunner(threading.Event(),
                                       on_saved=lambda _e, _n, shared: seen.append(shared))
    obtained = obtain(points, runner=runner)
    assert seen == [None] and obtained.entry == entry_path(points)
    assert obtained.complex.points.base is None  # read from the entry, not mapped


def test_the_folder_goes_once_the_window_and_the_topology_process_mapped_it():
    """The whole path: the runner maps the table, the topology process maps it and lets go;
    then the folder is gone while both still use the pages, the topology equals the pass
    here, and the entry (written by the build process) is rewritten with the signatures."""
    points = np.random.default_rng(3).random((4000, 3))
    started: list[TopologyChild] = []
    shared_seen: list[SharedTable] = []

    def on_saved(entry: Path, _n: int, shared: SharedTable | None) -> None:
        shared_seen.append(shared)
        started.append(TopologyChild(entry, threading.Event(), shared=shared))

    runner = build_process.ChildRunner(threading.Event(), on_saved=on_saved)
    obtained = obtain(points, runner=runner)
    ac = obtained.complex
    parts = started[0].parts(ac, never)
    assert started[0].wait(60)
    assert shared_seen[0] is not None and shared_seen[0].folder.removed and my_shared() == []
    here = AlphaComplex.from_points(points)
    np.testing.assert_array_equal(parts.signatures.betti, here.signatures().betti)
    assert parts.optimal_alpha == here.optimal_alpha() and parts.entry_saved
    upgraded, damaged = read_entry(obtained.entry, len(points), Mode())
    assert not damaged and upgraded.has_signatures
    folder = shared_seen[0].folder.path
    assert mapped_here(folder)  # the window's table lives on in its mapping ...
    del ac, obtained, runner, upgraded, parts
    started.clear()
    gc.collect()
    assert mapped_here(folder) == []  # ... and goes with it


def test_without_a_topology_process_the_folder_goes_after_the_window_mapped_it():
    points = np.random.default_rng(4).random((3000, 2))
    obtained = obtain(points, runner=build_process.ChildRunner(threading.Event()))
    assert len(obtained.complex.points) == 3000 and my_shared() == []


@pytest.mark.parametrize("stage", ["Delaunay triangulation", "handing the table over",
                                   "loading the table"])
def test_cancel_at_every_stage_leaves_nothing_in_shared_memory(stage):
    """Cancel while it builds, while it writes the shared table, and after the hand-over
    (while it writes the entry): Cancelled, no process, no folder, the entry whole or
    absent."""
    points = np.random.default_rng(5).random((60_000, 3))
    cancel = threading.Event()
    started: list[TopologyChild] = []

    def progress(_fraction: float, reported: str) -> None:
        if reported == stage:
            cancel.set()

    def on_saved(entry: Path, _n: int, shared: SharedTable | None) -> None:
        started.append(TopologyChild(entry, cancel, shared=shared))

    runner = build_process.ChildRunner(cancel, on_saved=on_saved)
    with pytest.raises(Cancelled):
        obtain(points, runner=runner, progress=progress)
    for child in started:
        child.stop()
    assert multiprocessing.active_children() == [] and my_shared() == []  # killed at once
    assert read_entry(entry_path(points), len(points), Mode())[1] is None


def test_a_child_that_dies_after_a_shared_hand_over_leaves_a_working_table(tmp_path,
                                                                          monkeypatch):
    """The child handed the table over in shared memory, then died before its entry was
    written: the window keeps a whole, working table; the folder is gone; no entry."""
    points = np.random.default_rng(6).random((3000, 3))

    def dies_after_handing_over(work, args, _progress, _cancel, _name, hand, finish) -> str:
        source, target, job = args
        job = replace(job, save_to=None)  # the body stops before its entry is written
        messages: list[object] = []
        try:
            work(source, target, job, never, messages.append)
            hand(messages[0])  # the table; the process dies before its opening alpha
            raise AlphaScoopError("the background process stopped without a result")
        finally:
            finish()

    monkeypatch.setattr(build_process, "run_in_child", dies_after_handing_over)
    runner = build_process.ChildRunner(threading.Event())
    obtained = obtain(points, runner=runner)
    ac = obtained.complex
    assert my_shared() == [] and obtained.entry is None and my_scratch() == []
    assert runner.handed_over(ac).cursor is not None
    here = AlphaComplex.from_points(points)
    assert ac.optimal_alpha() == here.optimal_alpha()
    assert ac.shape(here.optimal_alpha()).cells.tobytes() == (
        here.shape(here.optimal_alpha()).cells.tobytes())


def test_the_topology_process_rewrites_the_entry_only_after_the_build_wrote_it(tmp_path):
    """The build process holds its lock while it writes the entry: the topology process
    (its body, run here) hands over, then waits; released, it rewrites the entry."""
    points = np.random.default_rng(7).random((2000, 3))
    ac = AlphaComplex.from_points(points)
    shared, entry, saving = tmp_path / "shared", tmp_path / "entry.npz", tmp_path / "saving"
    shared.mkdir()
    AlphaComplex.from_points(points).save(entry)  # the build process's entry
    from core.storage.tables import save_mapped
    assert save_mapped(ac, shared)
    stages: list[str] = []
    handed = threading.Event()

    def progress(_fraction: float, stage: str) -> None:
        stages.append(stage)
        if stage == HANDED_OVER:
            handed.set()

    with open(saving, "wb") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        body = threading.Thread(target=topology_in_child, args=(TopologyJob(
            str(shared), str(entry), str(tmp_path / "topology.npz"), str(saving)), progress,
            lambda _message: None))
        body.start()
        assert handed.wait(60)
        body.join(0.5)
        assert body.is_alive()  # waits for the lock ...
        assert not AlphaComplex.load(entry).has_signatures
    body.join(60)  # ... and rewrites once it is released
    assert not body.is_alive() and AlphaComplex.load(entry).has_signatures


def test_an_entry_the_build_could_not_write_is_not_made_by_the_topology(tmp_path):
    points = np.random.default_rng(8).random((2000, 3))
    shared, entry = tmp_path / "shared", tmp_path / "entry.npz"
    shared.mkdir()
    from core.storage.tables import save_mapped
    assert save_mapped(AlphaComplex.from_points(points), shared)
    topology_in_child(TopologyJob(str(shared), str(entry), str(tmp_path / "topology.npz"),
                                  str(tmp_path / "gone.lock")), never, lambda _message: None)
    assert not entry.exists()


KILLED_WINDOW = """
import sys, time
from app.shared_folder import SharedFolder
folder = SharedFolder()
(folder.path / "points.npy").write_bytes(b"x" * 4096)
print(folder.path, flush=True)
time.sleep(60)
"""


def test_a_killed_window_leaves_nothing_in_shared_memory_after_the_next_start():
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    window = subprocess.Popen([sys.executable, "-c", KILLED_WINDOW], env=env,
                              stdout=subprocess.PIPE, text=True)
    try:
        folder = Path(window.stdout.readline().strip())
        assert folder.is_dir() and folder.parent == child_process.SHARED_ROOT
        assert folder not in child_process.remove_orphans()  # its window lives
    finally:
        window.kill()
        window.wait()
        window.stdout.close()
    deadline = time.monotonic() + 10
    removed: list[Path] = []
    while folder.exists() and time.monotonic() < deadline:  # the kernel drops its lock
        removed += child_process.remove_orphans()
        time.sleep(0.05)
    assert folder in removed and not folder.exists()


def test_a_shared_folder_goes_when_its_last_holder_lets_go():
    folder = SharedFolder()
    first, second = folder.hold(), folder.hold()
    folder.release()
    folder.release()  # counted once
    first()
    first()
    assert folder.path.is_dir() and not folder.removed
    second()
    assert folder.removed and not folder.path.exists()
    with pytest.raises(ValueError):
        folder.hold()



def wait_until(condition, seconds: float = 60) -> bool:
    """Poll condition until it holds or seconds passed; whether it held."""
    deadline = time.monotonic() + seconds
    while not condition() and time.monotonic() < deadline:
        time.sleep(0.05)
    return condition()


@pytest.mark.parametrize("cancel_after", [False, True])
def test_the_runner_leaves_the_entry_to_its_child_which_a_cancel_still_stops(cancel_after):
    """Without the signatures the runner returns once it has the table and the opening
    alpha; the child writes the entry on its own (the entry is already named), then ends
    and its scratch folder goes. A cancel (a newer open) kills it: the entry is then
    absent or whole, never damaged."""
    points = np.random.default_rng(10).random((120_000, 3))
    cancel = threading.Event()
    runner = build_process.ChildRunner(cancel)
    obtained = obtain(points, runner=runner)
    handed = runner.handed_over(obtained.complex)
    assert handed.saving and handed.opening_alpha is not None
    assert obtained.entry == entry_path(points)
    if cancel_after:
        cancel.set()
    assert wait_until(lambda: not multiprocessing.active_children() and my_scratch() == [])
    if not cancel_after:
        assert entry_path(points).is_file()
    assert read_entry(entry_path(points), len(points), Mode())[1] is None
    assert my_shared() == []

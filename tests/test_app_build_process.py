"""Builds in a child process: same table, errors carried over, cancel kills it at once."""

from __future__ import annotations

import multiprocessing
import signal
import threading

import numpy as np
import pytest
from child_cancel import cancel_at

from app import build_process, child_process
from app.messages import BuildJob, OpeningFound, TableHandedOver
from core import AlphaComplex
from core.cache import entry_path, read_entry
from core.errors import AlphaScoopError, Cancelled, InputError
from core.modes.alpha_modes import Mode
from core.obtain import BuildRequest, HandOver, obtain
from core.topology.opening import opening_alpha_of


@pytest.fixture
def in_process(monkeypatch, tmp_path):
    """Every build goes to a child process; a private cache folder."""
    monkeypatch.setattr(build_process, "IN_THREAD_BELOW", 0)
    monkeypatch.setenv("ALPHASCOOP_CACHE_DIR", str(tmp_path / "cache"))


def never(*_args) -> None:
    """A progress callback that ignores its reports."""


def child_obtain(points, progress=never, cancel=None, use_cache=True):
    """The window's path: obtain with signatures, built by the child-process runner."""
    return obtain(points, signatures=True, use_cache=use_cache, progress=progress,
                  runner=build_process.ChildRunner(cancel or threading.Event()))


def test_child_build_equals_the_build_here_and_fills_the_cache(in_process):
    points = np.random.default_rng(0).random((3000, 3))
    stages: list[str] = []
    obtained = child_obtain(points, lambda f, s: stages.append(s))
    assert obtained.source == "built" and obtained.entry == entry_path(points)
    ac = obtained.complex
    here = AlphaComplex.from_points(points)
    for k in range(4):
        np.testing.assert_array_equal(ac.simplices(k), here.simplices(k))
        np.testing.assert_array_equal(ac.intervals(k), here.intervals(k))
    assert ac.has_signatures  # came with the table: no topology pass here
    np.testing.assert_array_equal(ac.signatures().betti, here.signatures().betti)
    assert ac.optimal_alpha() == here.optimal_alpha()
    assert "Delaunay triangulation" in stages and "topology" in stages
    assert entry_path(points).is_file()
    again: list[str] = []
    assert child_obtain(points, lambda f, s: again.append(s)).source == "cache"
    assert again == ["loaded from cache"]


def test_without_a_cache_the_child_hands_over_a_temporary_file(in_process):
    points = np.random.default_rng(1).random((500, 2))
    ac = child_obtain(points, use_cache=False).complex
    assert len(ac.points) == 500 and not entry_path(points).exists()


def test_bad_points_raise_the_childs_input_error(in_process):
    collinear = np.column_stack([np.arange(100.0), 2 * np.arange(100.0), np.zeros(100)])
    with pytest.raises(InputError, match=r"collinear|line"):
        child_obtain(collinear)


def test_cancel_during_the_triangulation_kills_the_child_while_it_works(in_process):
    """The child says it is triangulating (seconds of Qhull without a message): it is alive
    when Cancel is pressed, and gone soon after, killed (SIGKILL), not finished."""
    points = np.random.default_rng(2).random((150_000, 3))
    seen = cancel_at("Delaunay triangulation",
                     lambda progress, cancel: child_obtain(points, progress, cancel))
    working, outcome = seen.working, seen.outcome
    assert len(working) == 1 and working[0].name == "alphascoop-build"
    assert seen.alive_at_cancel == [True]
    assert len(outcome) == 1 and isinstance(outcome[0], Cancelled)
    assert working[0].exitcode == -signal.SIGKILL  # killed mid-work: it did not finish
    assert multiprocessing.active_children() == []
    assert not entry_path(points).exists()


def test_a_child_that_dies_is_a_readable_error():
    receiver, sender = multiprocessing.Pipe(duplex=False)
    sender.close()

    class Dead:
        exitcode = -9

        def join(self, _timeout=None) -> None:
            return None

    with pytest.raises(AlphaScoopError, match="exit code -9"):
        child_process._follow(Dead(), receiver, never, threading.Event())


def test_a_cached_table_without_signatures_is_upgraded_in_place(in_process):
    from core.cache import load_cached

    points = np.random.default_rng(5).random((800, 3))
    obtain(points)  # as `alphascoop export --alpha R` leaves it: no signatures
    assert not load_cached(points).has_signatures
    obtained = child_obtain(points)
    assert obtained.source == "cache" and obtained.complex.has_signatures
    assert load_cached(points).has_signatures


def test_the_child_finds_the_quick_opening_alpha_while_it_saves(in_process):
    points = np.random.default_rng(5).random((3000, 3))
    runner = build_process.ChildRunner(threading.Event())
    ac = obtain(points, runner=runner).complex
    assert not ac.has_signatures
    assert runner.handed_over(ac).opening_alpha == opening_alpha_of(ac.index, ac.points)
    assert runner.handed_over(ac).opening_alpha == AlphaComplex.from_points(
        points).default_alpha()
    with_signatures = build_process.ChildRunner(threading.Event())
    built = obtain(points + 1.0, signatures=True, runner=with_signatures).complex
    assert with_signatures.handed_over(built).opening_alpha is None  # the signatures hold it
    assert with_signatures.handed_over(built).cursor is not None
    assert runner.handed_over(built) == HandOver()  # not the complex it built



@pytest.mark.filterwarnings("error::pytest.PytestUnhandledThreadExceptionWarning")
def test_an_opening_alpha_the_child_cannot_find_is_left_to_the_window(tmp_path, monkeypatch):
    """The child's body, run here: a failing search beside the save leaves the table
    written and the opening alpha to the window (None), with no traceback."""
    def out_of_memory(*_args):
        raise MemoryError("no room beside the save")

    monkeypatch.setattr(build_process, "opening_alpha_of", out_of_memory)
    points = np.random.default_rng(6).random((3000, 3))
    np.save(tmp_path / "points.npy", points)
    job = BuildJob(Mode(), False, None, None, None)
    handed: list[object] = []
    answer = build_process.build_in_child(
        str(tmp_path / "points.npy"), str(tmp_path / "table.npz"), job, never, handed.append)
    assert answer == OpeningFound(None)
    assert handed == [TableHandedOver(str(tmp_path / "table.npz"), False,
                                      str(tmp_path / build_process.ORDERS_NAME),
                                      str(tmp_path / build_process.SAVING_NAME))]
    assert len(AlphaComplex.load(handed[0].table).simplices(3)) == len(
        AlphaComplex.from_points(points).simplices(3))


def test_the_handed_over_cursor_equals_the_tables_own(in_process):
    """The cursor the runner made from the child's sort orders hands out the same shapes,
    row for row, as the loaded table's own cursor."""
    points = np.random.default_rng(7).random((3000, 3))
    runner = build_process.ChildRunner(threading.Event())
    ac = obtain(points, runner=runner).complex
    handed = runner.handed_over(ac).cursor
    own = ac.cursor()
    spectrum = ac.spectrum()
    for alpha in spectrum[np.linspace(0, len(spectrum) - 1, 15).astype(int)]:
        mine, theirs = own.move(alpha), handed.move(alpha)
        np.testing.assert_array_equal(mine.regular_facets, theirs.regular_facets)
        for k in range(3):
            np.testing.assert_array_equal(mine.singular(k), theirs.singular(k))


def test_a_child_killed_while_it_saves_leaves_no_partial_entry(in_process):
    """Cancel a moment after the child handed the table over in shared memory and started
    writing the entry (a few hundred ms of writes at this size): the entry is absent or
    whole (atomic write), never damaged, and the next lookup removes the killed writer's
    temporary file."""
    points = np.random.default_rng(8).random((120_000, 3))
    cancel = threading.Event()

    def progress(_fraction: float, stage: str) -> None:
        if stage == "loading the table":
            threading.Timer(0.05, cancel.set).start()

    with pytest.raises(Cancelled):
        child_obtain(points, progress, cancel)
    entry = entry_path(points)
    if entry.exists():  # it finished the rename before the kill: a whole table
        assert len(AlphaComplex.load(entry).points) == len(points)
    assert read_entry(entry, len(points), Mode())[1] is None  # never a damaged entry
    left = [path.name for path in entry.parent.iterdir()] if entry.parent.exists() else []
    assert left in ([], [entry.name])
    assert multiprocessing.active_children() == []


def test_a_child_that_dies_after_the_hand_over_leaves_the_table(tmp_path, monkeypatch):
    """The table and orders were handed over, then the child died (out of memory, say):
    the runner keeps the table and its cursor and leaves the opening alpha to the window."""
    points = np.random.default_rng(9).random((3000, 3))
    np.save(tmp_path / "points.npy", points)
    job = BuildJob(Mode(), False, None, None, None)
    handed: list[object] = []
    build_process.build_in_child(str(tmp_path / "points.npy"), str(tmp_path / "table.npz"),
                                 job, never, handed.append)

    def dies_after_handing_over(_work, _args, _progress, _cancel, _name, hand, finish) -> str:
        try:
            hand(handed[0])
            raise AlphaScoopError("the background process stopped without a result")
        finally:
            finish()

    monkeypatch.setattr(build_process, "IN_THREAD_BELOW", 0)
    monkeypatch.setattr(build_process, "run_in_child", dies_after_handing_over)
    runner = build_process.ChildRunner(threading.Event())
    ac = runner(BuildRequest(points))
    assert len(ac.points) == 3000 and handed[0].orders is not None
    assert runner.handed_over(ac).opening_alpha is None
    assert runner.handed_over(ac).cursor is not None

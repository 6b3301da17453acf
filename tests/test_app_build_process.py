"""Builds in a child process: same table, errors carried over, cancel kills it at once."""

from __future__ import annotations

import multiprocessing
import threading
import time

import numpy as np
import pytest

from app import build_process
from core import AlphaComplex
from core.cache import entry_path
from core.errors import AlphaScoopError, Cancelled, InputError


@pytest.fixture
def in_process(monkeypatch, tmp_path):
    """Every build goes to a child process; a private cache folder."""
    monkeypatch.setattr(build_process, "IN_THREAD_BELOW", 0)
    monkeypatch.setenv("ALPHASCOOP_CACHE_DIR", str(tmp_path / "cache"))


def never(*_args) -> None:
    """A progress callback that ignores its reports."""


def test_child_build_equals_the_build_here_and_fills_the_cache(in_process):
    points = np.random.default_rng(0).random((3000, 3))
    stages: list[str] = []
    ac = build_process.build(points, lambda f, s: stages.append(s), threading.Event())
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
    build_process.build(points, lambda f, s: again.append(s), threading.Event())
    assert again == ["loaded from cache"]


def test_without_a_cache_the_child_hands_over_a_temporary_file(in_process):
    points = np.random.default_rng(1).random((500, 2))
    ac = build_process.build(points, never, threading.Event(), use_cache=False)
    assert len(ac.points) == 500 and not entry_path(points).exists()


def test_bad_points_raise_the_childs_input_error(in_process):
    collinear = np.column_stack([np.arange(100.0), 2 * np.arange(100.0), np.zeros(100)])
    with pytest.raises(InputError, match=r"collinear|line"):
        build_process.build(collinear, never, threading.Event())


def test_cancel_during_the_triangulation_kills_the_child_at_once(in_process):
    points = np.random.default_rng(2).random((400_000, 3))
    cancel, started = threading.Event(), threading.Event()

    def progress(fraction: float, stage: str) -> None:
        if stage == "Delaunay triangulation":
            started.set()

    outcome: list[BaseException] = []

    def run() -> None:
        try:
            build_process.build(points, progress, cancel)
        except BaseException as error:  # recorded for the assertion below
            outcome.append(error)

    thread = threading.Thread(target=run)
    thread.start()
    assert started.wait(60)
    cancel.set()
    began = time.perf_counter()
    thread.join(30)
    assert not thread.is_alive()
    assert time.perf_counter() - began < 5.0  # the build itself takes about 30 s
    assert len(outcome) == 1 and isinstance(outcome[0], Cancelled)
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
        build_process._follow(Dead(), receiver, never, threading.Event())


def test_a_cached_table_without_signatures_is_upgraded_in_place(in_process):
    from core.cache import build_cached, load_cached

    points = np.random.default_rng(5).random((800, 3))
    build_cached(points)  # as `alphascoop export --alpha R` leaves it: no signatures
    assert not load_cached(points).has_signatures
    ac = build_process.build(points, never, threading.Event())
    assert ac.has_signatures and load_cached(points).has_signatures

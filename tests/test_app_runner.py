"""app.jobs.Runner, the one background runner of loads and exports: one outcome per request,
stale requests dropped in one place, cancel, exclusivity and shut-down."""

from __future__ import annotations

import gc
import threading
import weakref

import pytest

from app.jobs import Job, Runner
from core.errors import InputError

TIMEOUT_MS = 10_000


def recorder(runner: Runner) -> list[tuple]:
    """Every signal the runner sends, in order: (name, *arguments)."""
    seen: list[tuple] = []
    for name in ("progress", "finished", "failed", "cancelled", "dropped"):
        getattr(runner, name).connect(lambda *args, name=name: seen.append((name, *args)))
    return seen


def blocked_job(started: threading.Event, release: threading.Event, result="old") -> Job:
    """A job that reports once, waits for release, reports again and returns result."""

    def work(progress, cancel):
        progress(0.1, "first")
        started.set()
        release.wait(10)
        progress(0.9, "second")  # raises Cancelled once cancel was set
        return result

    return Job("blocked", work)


def test_a_job_reports_progress_then_its_result(qtbot) -> None:
    runner = Runner()
    seen = recorder(runner)
    with qtbot.waitSignal(runner.finished, timeout=TIMEOUT_MS):
        request = runner.start(Job("sum", lambda progress, cancel: progress(0.5, "half") or 3))
    assert seen == [("progress", request, 0.5, "half"), ("finished", request, 3)]
    qtbot.waitUntil(lambda: not runner.is_busy(), timeout=TIMEOUT_MS)


def test_a_newer_request_supersedes_the_older_whose_outcome_is_dropped(qtbot) -> None:
    runner = Runner()
    seen = recorder(runner)
    started, release = threading.Event(), threading.Event()
    first = runner.start(blocked_job(started, release))
    assert started.wait(10)
    with qtbot.waitSignal(runner.finished, timeout=TIMEOUT_MS):
        second = runner.start(Job("new", lambda progress, cancel: "new"))
        release.set()
    assert second == first + 1 == runner.current
    assert ("dropped", first, "cancelled") in seen
    outcomes = [event for event in seen if event[0] != "progress"]
    assert outcomes[-1] == ("finished", second, "new")
    assert [event for event in outcomes if event[1] == first] == [("dropped", first, "cancelled")]


def test_cancel_ends_the_current_request_as_cancelled(qtbot) -> None:
    runner = Runner()
    started, release = threading.Event(), threading.Event()
    request = runner.start(blocked_job(started, release))
    assert started.wait(10)
    with qtbot.waitSignal(runner.cancelled, timeout=TIMEOUT_MS) as blocker:
        runner.cancel()
        release.set()
    assert blocker.args == [request]


@pytest.mark.parametrize(("error", "expected"), [
    (InputError("bad.ply: no vertices"), "boom failed: bad.ply: no vertices"),
    (RuntimeError("renderer fell over"), "boom failed: renderer fell over"),
])
def test_a_failure_is_one_line_never_a_traceback(qtbot, error, expected) -> None:
    runner = Runner()

    def work(progress, cancel):
        raise error

    with qtbot.waitSignal(runner.failed, timeout=TIMEOUT_MS) as blocker:
        request = runner.start(Job("boom", work))
    assert blocker.args == [request, expected]


def test_the_job_explains_its_own_failures(qtbot) -> None:
    runner = Runner()

    def work(progress, cancel):
        raise MemoryError

    with qtbot.waitSignal(runner.failed, timeout=TIMEOUT_MS) as blocker:
        runner.start(Job("open", work, lambda error: f"no memory ({type(error).__name__})"))
    assert blocker.args[1] == "no memory (MemoryError)"


def test_an_exclusive_runner_refuses_a_second_job_while_one_runs(qtbot) -> None:
    runner = Runner(exclusive=True)
    started, release = threading.Event(), threading.Event()
    first = runner.start(blocked_job(started, release))
    assert started.wait(10)
    assert runner.start(Job("second", lambda progress, cancel: None)) is None
    assert runner.is_busy() and runner.title == "blocked"
    with qtbot.waitSignal(runner.finished, timeout=TIMEOUT_MS) as blocker:
        release.set()
    assert blocker.args == [first, "old"]
    qtbot.waitUntil(lambda: not runner.is_busy(), timeout=TIMEOUT_MS)
    assert runner.start(Job("third", lambda progress, cancel: None)) == first + 1
    runner.wait()


def test_after_shut_down_nothing_reaches_the_listeners(qtbot) -> None:
    runner = Runner()
    seen = recorder(runner)
    started, release = threading.Event(), threading.Event()

    def stuck(progress, cancel):  # like a Delaunay build: never looks at cancel
        started.set()
        release.wait(10)
        return "late"

    request = runner.start(Job("stuck", stuck))
    assert started.wait(10)
    assert runner.shut_down(50) is False
    release.set()
    assert runner.wait(TIMEOUT_MS)
    qtbot.waitUntil(lambda: not runner.is_busy(), timeout=TIMEOUT_MS)
    assert [event for event in seen if event[0] in ("finished", "failed", "cancelled")] == []
    assert ("dropped", request, "cancelled") in seen


def test_the_runner_keeps_nothing_a_finished_job_held(qtbot) -> None:
    """Once its outcome is delivered, a job and what its work captured (a dataset) are freed:
    the runner keeps only the title."""
    class Payload:
        pass

    held = Payload()
    ref = weakref.ref(held)
    runner = Runner()

    def work(progress, cancel, held=held):
        return None

    with qtbot.waitSignal(runner.finished, timeout=TIMEOUT_MS):
        runner.start(Job("holds a payload", work))
    qtbot.waitUntil(lambda: not runner.is_busy(), timeout=TIMEOUT_MS)
    del held, work
    gc.collect()
    assert ref() is None and runner.title == "holds a payload"


class Escaped(BaseException):
    """A BaseException of a library's own (like gevent's GreenletExit): no Exception."""


@pytest.mark.parametrize(("error", "line"), [
    (KeyboardInterrupt(), "boom stopped: KeyboardInterrupt"),
    (SystemExit(3), "boom stopped: SystemExit (3)"),
    (GeneratorExit(), "boom stopped: GeneratorExit"),
    (Escaped("out"), "boom stopped: Escaped (out)"),
])
def test_a_job_that_raises_a_base_exception_fails_like_any_other(
        qtbot, monkeypatch, error, line) -> None:
    """A BaseException out of a job used to kill the runner's thread with no outcome: the
    progress stayed up, is_busy() stayed True (an exclusive runner refused every later job)
    and no later job ran. Now it is a failure; SystemExit and KeyboardInterrupt still end
    the thread they were raised in (its excepthook sees them), and the next job gets a new
    one; no thread is left behind."""
    hooked: list[type] = []
    monkeypatch.setattr(threading, "excepthook", lambda args: hooked.append(args.exc_type))
    runner = Runner(exclusive=True)
    seen = recorder(runner)
    ran_in: list[threading.Thread] = []

    def work(progress, cancel):
        ran_in.append(threading.current_thread())
        raise error

    with qtbot.waitSignal(runner.failed, timeout=TIMEOUT_MS) as blocker:
        request = runner.start(Job("boom", work))
    assert blocker.args == [request, line]
    qtbot.waitUntil(lambda: not runner.is_busy(), timeout=TIMEOUT_MS)
    with qtbot.waitSignal(runner.finished, timeout=TIMEOUT_MS) as blocker:
        later = runner.start(Job("later", lambda progress, cancel: ran_in.append(
            threading.current_thread()) or "done"))
    assert blocker.args == [later, "done"]
    assert [event[0] for event in seen] == ["failed", "finished"]
    stops = isinstance(error, (KeyboardInterrupt, SystemExit))
    ran_in[0].join(TIMEOUT_MS / 1000)
    assert ran_in[0].is_alive() is not stops and (ran_in[1] is ran_in[0]) is not stops
    assert hooked == ([type(error)] if stops else [])
    alive = [thread for thread in threading.enumerate() if thread.name == "alphascoop-job"
             and thread in ran_in]
    assert alive == [ran_in[1]]


def test_a_job_queued_behind_one_that_ends_the_thread_still_runs(qtbot, monkeypatch) -> None:
    """The thread a SystemExit ends hands the jobs queued meanwhile to a new thread."""
    monkeypatch.setattr(threading, "excepthook", lambda args: None)
    runner = Runner()
    seen = recorder(runner)
    started, release = threading.Event(), threading.Event()

    def exits(progress, cancel):
        started.set()
        release.wait(10)
        raise SystemExit

    first = runner.start(Job("exits", exits))
    assert started.wait(10)
    with qtbot.waitSignal(runner.finished, timeout=TIMEOUT_MS) as blocker:
        second = runner.start(Job("queued", lambda progress, cancel: "ran"))
        release.set()
    assert blocker.args == [second, "ran"]
    qtbot.waitUntil(lambda: not runner.is_busy(), timeout=TIMEOUT_MS)
    assert ("dropped", first, "failed") in seen  # in either order: two threads reported


def test_a_failing_explain_still_gives_the_default_line(qtbot) -> None:
    runner = Runner()

    def work(progress, cancel):
        raise OSError("disk full")

    def explain(error):
        raise KeyError("no such message")

    with qtbot.waitSignal(runner.failed, timeout=TIMEOUT_MS) as blocker:
        runner.start(Job("save", work, explain))
    assert blocker.args[1] == "save failed: disk full"
    qtbot.waitUntil(lambda: not runner.is_busy(), timeout=TIMEOUT_MS)

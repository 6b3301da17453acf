"""Cancel a background child process at the moment it reports a stage, and record what the
tests of the build and topology processes assert: the child alive then, killed after."""

from __future__ import annotations

import multiprocessing
import threading
from collections.abc import Callable
from dataclasses import dataclass, field

LIVENESS_BOUND_S = 120  # generous: the child is killed within a poll (0.1 s) of Cancel


@dataclass
class Cancelling:
    """What happened: the children seen at the stage, whether they were alive, the error."""

    working: list[multiprocessing.Process] = field(default_factory=list)
    alive_at_cancel: list[bool] = field(default_factory=list)
    outcome: list[BaseException] = field(default_factory=list)


def cancel_at(stage: str, work: Callable[[Callable[[float, str], None], threading.Event],
                                         object]) -> Cancelling:
    """Run work(progress, cancel) in a thread and set cancel when the child reports `stage`
    (the progress callback runs in the thread that owns the child); wait for the thread."""
    seen, cancel = Cancelling(), threading.Event()

    def progress(_fraction: float, reported: str) -> None:
        if reported == stage and not seen.working:  # sent by the child
            seen.working.extend(multiprocessing.active_children())
            seen.alive_at_cancel.extend(child.is_alive() for child in seen.working)
            cancel.set()

    def run() -> None:
        try:
            work(progress, cancel)
        except BaseException as error:  # recorded for the test's assertions
            seen.outcome.append(error)

    thread = threading.Thread(target=run)
    thread.start()
    thread.join(LIVENESS_BOUND_S)
    assert not thread.is_alive(), "the child was not stopped"
    return seen

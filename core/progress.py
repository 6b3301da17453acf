"""The progress callback every long computation takes, and a helper to report parts of it."""

from __future__ import annotations

from collections.abc import Callable

#: `progress(fraction, stage)`: fraction in [0, 1] done, stage a short label; raising
#: core.errors.Cancelled from it stops the computation.
Progress = Callable[[float, str], None]


class Stepper:
    """Calls an optional Progress; `part(start, share)` maps a sub-task's [0, 1] onto
    [start, start + share] of it (None when there is no callback, so sub-tasks skip work)."""

    def __init__(self, progress: Progress | None) -> None:
        self.progress = progress

    def __call__(self, fraction: float, stage: str) -> None:
        if self.progress is not None:
            self.progress(fraction, stage)

    def part(self, start: float, share: float) -> Progress | None:
        """A Progress for a sub-task covering [start, start + share], or None."""
        if self.progress is None:
            return None
        report = self.progress
        return lambda fraction, stage: report(start + share * fraction, stage)

"""Back/forward through the alphas visited: undo for the slider (no Qt).

Visits close together in time (a drag, a held arrow key) are one visit: the newest replaces
the last entry when it comes within `merge_seconds` of it.
"""

from __future__ import annotations

import time
from collections.abc import Callable

MERGE_SECONDS = 0.6
MAX_ENTRIES = 200


class AlphaHistory:
    """A browser-like list of spectrum indexes with a current position."""

    def __init__(self, merge_seconds: float = MERGE_SECONDS,
                 clock: Callable[[], float] = time.monotonic) -> None:
        """Empty; `clock()` gives seconds (tests pass their own)."""
        self.merge_seconds = merge_seconds
        self.clock = clock
        self.entries: list[int] = []
        self.current = -1
        self._last_visit = -float("inf")

    def reset(self, index: int) -> None:
        """Start over at index (a new dataset)."""
        self.entries, self.current = [index], 0
        self._last_visit = -float("inf")

    def visit(self, index: int) -> None:
        """Record a move to index; drops the forward entries, merges quick successive moves."""
        now = self.clock()
        del self.entries[self.current + 1:]
        if self.entries and self.entries[-1] == index:
            return
        if now - self._last_visit < self.merge_seconds:
            self.entries[-1] = index
        else:
            self.entries.append(index)
        del self.entries[:-MAX_ENTRIES]
        self.current = len(self.entries) - 1
        self._last_visit = now

    def can_back(self) -> bool:
        """True when back() has somewhere to go."""
        return self.current > 0

    def can_forward(self) -> bool:
        """True when forward() has somewhere to go."""
        return 0 <= self.current < len(self.entries) - 1

    def back(self) -> int | None:
        """The previous index (None at the start)."""
        if self.current <= 0:
            return None
        self.current -= 1
        self._last_visit = -float("inf")
        return self.entries[self.current]

    def forward(self) -> int | None:
        """The next index after a back (None at the end)."""
        if self.current >= len(self.entries) - 1:
            return None
        self.current += 1
        self._last_visit = -float("inf")
        return self.entries[self.current]

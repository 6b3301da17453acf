"""What the window re-opens when a load it started (after releasing the shown dataset) is
cancelled or fails: the previous file, in its mode, read as it was (its table comes from the
cache, so that takes a few percent of a build), at the alpha the user had moved to."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from app.dataset import ImportOptions
from core.modes.alpha_modes import Mode


@dataclass(frozen=True)
class ReopenFallback:
    """The released dataset's file, its alpha mode, how it was read, and the alpha the user
    had moved to (None when the slider was not touched: it re-opens at its opening alpha)."""

    path: Path
    mode: Mode
    options: ImportOptions | None
    alpha: float | None = None


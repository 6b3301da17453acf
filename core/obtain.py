"""One path from points to a built complex, and where it came from.

`obtain` reads the table cache (core.cache); on a miss it has a runner build the complex
(in this thread by default; the window passes app.build_process's child-process runner, which
Cancel can kill) and the entry is stored. The result says what really happened: "built",
"cache" (a good entry was read) or "rebuilt" (an entry existed but was damaged or belonged to
other points, so it was removed and built again). Every caller (window, `alphascoop info` and
`export`, screenshots) goes through here.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Literal, Protocol

import numpy as np

from core.build.points import as_points
from core.cache import entry_exists, entry_path, read_entry, save_entry
from core.complex import AlphaComplex
from core.modes.alpha_modes import Mode
from core.progress import Progress
from core.query.cursor import ShapeCursor

Source = Literal["built", "cache", "rebuilt"]
SOURCES: tuple[Source, ...] = ("built", "cache", "rebuilt")
TABLE_SHARE, SAVE_START = 0.65, 0.95  # of a build's progress with signatures; topology between


@dataclass(frozen=True, eq=False)
class BuildRequest:
    """What a runner builds: (n, d) float64 points, optional (n,) squared-radius `weights`,
    the alpha `mode` with its given (n, d) `normals`, whether to compute the `signatures` too,
    the cache entry to `save_to` (None: keep it in memory only) and the triangulation
    `backend` ("qhull", "gmsh", None = automatic: core/pipeline.py)."""

    points: np.ndarray
    weights: np.ndarray | None = None
    mode: Mode = field(default_factory=Mode)
    normals: np.ndarray | None = None
    signatures: bool = False
    save_to: Path | None = None
    backend: str | None = None

    def run(self, progress: Progress | None = None) -> tuple[AlphaComplex, Path | None]:
        """Build here: (the complex, the entry it was saved to, or None when not saved)."""
        ac = self.build(progress)
        return ac, self.save(ac, progress)

    def build(self, progress: Progress | None = None) -> AlphaComplex:
        """The complex (with its signatures when asked), not saved; progress up to SAVE_START."""
        def step(fraction: float, stage: str) -> None:
            if progress is not None:
                progress(fraction, stage)

        share = TABLE_SHARE if self.signatures else SAVE_START
        extra = {} if self.weights is None else {"weights": self.weights}
        ac = AlphaComplex.from_points(self.points, lambda f, s: step(share * f, s),
                                      **extra, **self.mode.build_kwargs(self.normals),
                                      backend=self.backend)
        if self.signatures:
            step(TABLE_SHARE, "topology")
            ac.signatures()
        return ac

    def save(self, ac: AlphaComplex, progress: Progress | None = None) -> Path | None:
        """Save the built `ac` to save_to: the entry written, None when not saved (no entry
        asked, or the cache cannot be written)."""
        if self.save_to is None:
            return None
        if progress is not None:
            progress(SAVE_START, "saving the table")
        return save_entry(ac, self.save_to)


@dataclass(frozen=True)
class HandOver:
    """What a runner found beside the complex it built, so that its caller need not: the
    quick opening alpha (core.topology.opening.opening_alpha_of) and the slider's cursor; None for
    what it did not find. `saving`: the runner's process still writes the complex's cache
    entry (it handed the complex over first)."""

    opening_alpha: float | None = None
    cursor: ShapeCursor | None = None
    saving: bool = False


class Runner(Protocol):
    """Builds the complex of a request for `obtain`: in this thread (run_here) or elsewhere
    (the window's build process, app.build_process.ChildRunner)."""

    def __call__(self, request: BuildRequest, progress: Progress | None = None
                 ) -> AlphaComplex:
        """The complex of request, saved to request.save_to if it can be; Cancelled raised
        by progress stops it."""

    def handed_over(self, ac: AlphaComplex) -> HandOver:
        """What this runner found beside `ac` while building it (HandOver() for a complex
        it did not build last)."""


class BuildHere:
    """The default runner: builds in the calling thread and finds nothing beside."""

    def __call__(self, request: BuildRequest, progress: Progress | None = None
                 ) -> AlphaComplex:
        """The complex of request, saved to request.save_to if it can be."""
        return request.run(progress)[0]

    def handed_over(self, ac: AlphaComplex) -> HandOver:
        """Nothing: the caller finds the opening alpha and makes the cursor itself."""
        return HandOver()


run_here = BuildHere()


@dataclass(frozen=True, eq=False)
class Obtained:
    """A complex and where it came from ("built", "cache" or "rebuilt", then `damage` says
    why the entry was not used); `entry` is its cache
    file (None when the cache was not used or could not be written; a runner may still be
    writing it: HandOver.saving)."""

    complex: AlphaComplex
    source: Source
    entry: Path | None = None
    damage: str | None = None  # "rebuilt": what was wrong with the entry, in a few words

    @property
    def from_cache(self) -> bool:
        """True when the table was read from the cache rather than built."""
        return self.source == "cache"


def obtain(points: object, *, weights: object = None, mode: Mode | None = None,
           normals: np.ndarray | None = None, signatures: bool = False,
           use_cache: bool = True, cache_dir: str | Path | None = None,
           backend: str | None = None, runner: Runner | None = None,
           progress: Progress | None = None) -> Obtained:
    """The complex of (n, d) points (with (n,) squared-radius `weights`; in the alpha `mode`,
    with its given `normals`), from the cache in `cache_dir` (default core.cache.cache_dir())
    when it holds a good entry, else built by `runner` (default run_here) and stored.

    With `signatures` the topology is computed too (a cached entry without it is upgraded and
    rewritten). `backend` forces a triangulation backend ("qhull" or "gmsh"; a cached table
    another backend built is then built again). `use_cache=False` neither reads nor writes
    the cache. progress(fraction,
    stage) may raise core.errors.Cancelled to stop; the build's errors (InputError for points
    that make no complex) pass through.
    """
    try:
        coords = np.asarray(points, dtype=np.float64)
    except (TypeError, ValueError):
        coords = as_points(points)  # raises the InputError that says what is wrong
    w = None if weights is None else np.asarray(weights, dtype=np.float64)
    mode = mode or Mode()
    request = BuildRequest(coords, w, mode, normals, signatures, backend=backend)
    runner = runner or run_here
    if not use_cache:
        return Obtained(runner(request, progress), "built")
    path = entry_path(coords, mode, normals, w, folder=cache_dir)
    ac, damage = read_entry(path, len(coords), mode)
    if ac is not None and backend not in (None, ac.build_info.backend):
        ac = None  # the same table, but the caller asked for the other backend's build
    if ac is None:
        built = runner(replace(request, save_to=path), progress)
        saving = runner.handed_over(built).saving  # then the entry is on its way
        return Obtained(built, "built" if damage is None else "rebuilt",
                        path if saving or entry_exists(path) else None, damage)
    if progress is not None:
        progress(1.0, "loaded from cache")
    obtained = Obtained(ac, "cache", path)
    return add_topology(obtained) if signatures else obtained


def add_topology(obtained: Obtained) -> Obtained:
    """Compute the signatures (the topology pass) of obtained.complex if it lacks them and
    rewrite its cache entry with them, so that the next open skips that pass too.

    The window calls this in the background once the slider is live; obtain(signatures=True)
    calls it for a cached entry that `info`/`export` left without them.
    """
    ac = obtained.complex
    if ac.has_signatures:
        return obtained
    ac.signatures()
    entry = None if obtained.entry is None else save_entry(ac, obtained.entry)
    return Obtained(ac, obtained.source, entry, obtained.damage)

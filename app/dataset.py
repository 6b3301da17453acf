"""Loading and building a dataset (no Qt): read points, build the complex, pick a start alpha."""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from core import AlphaComplex

Progress = Callable[[float, str], None]
READ_SHARE, BUILD_SHARE = 0.1, 0.85


@dataclass(frozen=True)
class Dataset:
    """A built dataset: its source, complex, spectrum (s,) float64 and timings in seconds."""

    path: Path
    ac: AlphaComplex
    spectrum: np.ndarray
    optimal_alpha: float
    signatures: object | None
    n_input: int
    report: object | None
    load_seconds: float
    build_seconds: float


def read_pointset(path: Path):
    """A PointSet-like object (.points (n, d) float64, .report) for path."""
    try:
        from core.io import read_points
    except ImportError:
        from types import SimpleNamespace

        from app.loading import read_ply_points

        return SimpleNamespace(points=read_ply_points(path), report=None)
    return read_points(path)


def build_complex(pointset, progress: Progress) -> AlphaComplex:
    """The alpha complex of pointset: from the core cache when there is one."""
    try:
        from core.cache import build_cached
    except ImportError:
        return AlphaComplex.from_points(pointset.points, progress=progress)
    return build_cached(pointset, progress=progress)


def optimal_alpha(ac: AlphaComplex) -> float:
    """The alpha a dataset opens at: ac.optimal_alpha(), else the smallest covering alpha.

    The fallback is the smallest alpha at which every point lies in a cell of the complex.
    """
    if hasattr(ac, "optimal_alpha"):
        return float(ac.optimal_alpha())
    cells = ac.simplices(ac.dim)
    if len(cells) == 0:
        return 0.0
    enter = np.repeat(ac.intervals(ac.dim)[:, 0], cells.shape[1])
    first_cell = np.full(len(ac.points), np.inf)
    np.minimum.at(first_cell, cells.ravel(), enter)
    return float(np.max(first_cell[np.isfinite(first_cell)]))


def signatures_of(ac: AlphaComplex):
    """ac.signatures() (Betti numbers, measures over the spectrum), or None if not available."""
    return ac.signatures() if hasattr(ac, "signatures") else None


def load_dataset(path: str | Path, progress: Progress) -> Dataset:
    """Read and build path, reporting progress(fraction, stage); Cancelled stops it."""
    path = Path(path)
    started = time.perf_counter()
    progress(0.0, "reading")
    pointset = read_pointset(path)
    read_done = time.perf_counter()

    def build_progress(fraction: float, stage: str) -> None:
        progress(READ_SHARE + BUILD_SHARE * fraction, stage)

    ac = build_complex(pointset, build_progress)
    built = time.perf_counter()
    progress(READ_SHARE + BUILD_SHARE, "choosing alpha")
    alpha = optimal_alpha(ac)
    progress(READ_SHARE + BUILD_SHARE + 0.02, "signatures")
    signatures = signatures_of(ac)
    progress(1.0, "done")
    return Dataset(
        path=path, ac=ac, spectrum=ac.spectrum(), optimal_alpha=alpha, signatures=signatures,
        n_input=len(pointset.points), report=getattr(pointset, "report", None),
        load_seconds=read_done - started, build_seconds=built - read_done,
    )

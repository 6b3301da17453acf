"""Point sources read in chunks for tiled runs, and the first pass over them (bounds, count,
largest weight, flatness).

LAS/LAZ files are streamed with laspy's chunked reader, so no step holds all points (COPC
files node by node, and read by box through their octree: core.tiled.copc; big text and
PLY files: core.io.streams); other files are read whole by core.io (as the window and
`alphascoop` read them) and then handed on in chunks. Planar 3D input is projected on its
plane once, as core.build does.
"""

from __future__ import annotations

import os
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from core.build.points import Frame
from core.errors import FileFormatError, InputError
from core.tiled.memory import prepared

#: Points per chunk of a streamed source.
CHUNK_POINTS = 1 << 20
#: Least to largest eigenvalue of the scatter under which streamed 3D points are not
#: certainly spread: the exact flatness test (an SVD of all points) needs them in memory.
SPREAD_RATIO = 1e-9


@dataclass(frozen=True)
class ArraySource:
    """Points held in memory, handed on in chunks: `coords` (n, dim) as the complex is
    built on them (planar 3D projected: `frame`), `weights` (n,) or None."""

    coords: np.ndarray
    weights: np.ndarray | None
    frame: Frame | None
    ambient_dim: int
    chunk: int = CHUNK_POINTS

    @classmethod
    def from_points(cls, points: object, weights: np.ndarray | None = None,
                    chunk: int = CHUNK_POINTS) -> ArraySource:
        """A source of (n, 2|3) points (planar 3D projected on its plane)."""
        coords, frame, ambient = prepared(points)
        w = None if weights is None or not np.any(weights) else np.asarray(weights, float)
        return cls(coords, w, frame, ambient, chunk)

    @property
    def dim(self) -> int:
        """Dimension of the complex."""
        return self.coords.shape[1]

    def chunks(self) -> Iterator[tuple[np.ndarray, np.ndarray | None]]:
        """(coords, weights) chunks in input order."""
        for lo in range(0, len(self.coords), self.chunk):
            hi = lo + self.chunk
            yield self.coords[lo:hi], None if self.weights is None else self.weights[lo:hi]


@dataclass(frozen=True)
class LasSource:
    """A LAS/LAZ file streamed with laspy's chunk iterator (scale and offset applied)."""

    path: Path
    chunk: int = CHUNK_POINTS
    weights: None = None
    frame: None = None
    ambient_dim: int = 3
    dim: int = 3

    def chunks(self) -> Iterator[tuple[np.ndarray, None]]:
        """(coords, None) chunks in file order; rows with non-finite coordinates dropped
        (core.io does the same)."""
        import laspy

        try:
            with laspy.open(self.path) as reader:
                for records in reader.chunk_iterator(self.chunk):
                    xyz = np.column_stack([np.asarray(records.x, dtype=np.float64),
                                           np.asarray(records.y, dtype=np.float64),
                                           np.asarray(records.z, dtype=np.float64)])
                    yield xyz[np.isfinite(xyz).all(axis=1)], None
        except Exception as exc:  # laspy, lazrs or the OS on a corrupt or vanished file
            raise unreadable_las(self.path, exc) from exc


def unreadable_las(path: Path, exc: BaseException) -> FileFormatError:
    """The one-line error of a LAS/LAZ file laspy, lazrs or the OS could not read."""
    reason = str(exc).splitlines()[0] if str(exc) else type(exc).__name__
    return FileFormatError(f"{path}: not a readable LAS/LAZ file ({reason})")


@dataclass(frozen=True)
class Survey:
    """The first pass: `count` points, their box `lo`..`hi`, largest weight (0 classic)."""

    count: int
    lo: np.ndarray
    hi: np.ndarray
    max_weight: float


def survey(source) -> Survey:
    """Count, bounds and largest weight of a source in one pass; InputError for streamed 3D
    points that may be planar (they need the in-memory flatness test)."""
    count, lo, hi, wmax = 0, None, None, 0.0
    mean = scatter = None
    for coords, weights in source.chunks():
        if len(coords) == 0:
            continue
        lo = coords.min(axis=0) if lo is None else np.minimum(lo, coords.min(axis=0))
        hi = coords.max(axis=0) if hi is None else np.maximum(hi, coords.max(axis=0))
        if weights is not None:
            wmax = max(wmax, float(weights.max()))
        mean, scatter = _combined(count, mean, scatter, coords)
        count += len(coords)
    if count == 0:
        raise InputError("no points: the input is empty")
    if source.frame is None and source.dim == 3 and not _spread(scatter):
        raise InputError("these 3D points are (nearly) planar: a streamed tiled run cannot "
                         "decide their plane exactly; read them as 2D (--columns) instead")
    return Survey(count, lo, hi, wmax)


def _combined(n: int, mean, scatter, coords: np.ndarray):
    """Mean and scatter matrix of n points combined with a chunk (Chan's update: no
    cancellation from large coordinates)."""
    m = len(coords)
    c_mean = coords.mean(axis=0)
    centred = coords - c_mean
    c_scatter = centred.T @ centred
    if mean is None:
        return c_mean, c_scatter
    delta = c_mean - mean
    total = n + m
    return mean + delta * (m / total), scatter + c_scatter + np.outer(delta, delta) * (n * m
                                                                                      / total)


def _spread(scatter: np.ndarray) -> bool:
    """The scatter's least eigenvalue is certainly above flatness (SPREAD_RATIO)."""
    eigen = np.linalg.eigvalsh(scatter)
    return bool(eigen[0] > SPREAD_RATIO * eigen[-1])


def file_stamp(source) -> tuple[int, int] | None:
    """(size, modification time in ns) of a file source's file; None for points in memory."""
    path = getattr(source, "path", None)
    if path is None:
        return None
    try:
        status = os.stat(path)
    except OSError as exc:
        raise FileFormatError(f"{path}: cannot be read ({(exc.strerror or str(exc)).lower()})"
                              ) from exc
    return status.st_size, status.st_mtime_ns


def check_unchanged(source, stamp: tuple[int, int] | None) -> None:
    """FileFormatError if the source's file is not as `stamp` found it: its tiles were
    planned from earlier passes over it, and would no longer hold its points."""
    if stamp is not None and file_stamp(source) != stamp:
        raise FileFormatError(f"{source.path}: the file changed while it was read (a tiled "
                              "run reads it several times); run again once it is complete")


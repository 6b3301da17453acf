"""geogram's regular (weighted Delaunay) triangulation, compiled at install from the vendored
sources (core/backends/native: geogram's Delaunay PSM, BSD-3-Clause, exact predicates with
symbolic perturbation) into core.backends._geogram and called through ctypes, which releases
the GIL. Where the library was not built (no C++ compiler at install) `available()` is False
and weighted builds use Qhull (core.build.delaunay.regular_cells).
"""

from __future__ import annotations

import ctypes
import importlib.util
from functools import cache

import numpy as np

from core.errors import InputError

LIBRARY = "core.backends._geogram"  #: the compiled module (pyproject.toml's ext-modules)

_FLAT, _NO_MEMORY = 3, 5  # as_regular's codes (native/regular.cpp)

#: Most points geogram's 32-bit cell arrays can take, by dimension: its 3D arrays hold 4
#: indices for each of some 6.7 cells a point (geogram's own periodic build refuses n × 28 >
#: 2³¹ - 1), its 2D arrays 3 for each of some 2 cells a point; past it, Qhull.
MAX_POINTS = {2: (2**31 - 1) // 12, 3: (2**31 - 1) // 28}


class GeogramError(RuntimeError):
    """geogram could not triangulate these points (the caller falls back to Qhull)."""


@cache
def _library() -> ctypes.CDLL | None:
    """The compiled library with its C API declared, initialised; None where it was not built
    or cannot run (unloadable, or compiled with fused multiply-adds)."""
    spec = importlib.util.find_spec(LIBRARY)
    if spec is None or not spec.origin:
        return None
    try:
        lib = ctypes.CDLL(spec.origin)
    except OSError:
        return None
    lib.as_ready.argtypes = []
    lib.as_ready.restype = ctypes.c_int
    lib.as_regular.argtypes = [ctypes.c_int, ctypes.c_int64, ctypes.c_void_p, ctypes.c_void_p,
                               ctypes.POINTER(ctypes.c_void_p), ctypes.POINTER(ctypes.c_int64)]
    lib.as_regular.restype = ctypes.c_int
    lib.as_take.argtypes = [ctypes.c_void_p, ctypes.c_void_p, ctypes.c_void_p]
    lib.as_take.restype = None
    lib.as_free.argtypes = [ctypes.c_void_p]
    lib.as_free.restype = None
    return lib if lib.as_ready() == 1 else None


def available() -> bool:
    """Whether the compiled library is there and usable."""
    return _library() is not None


def regular_cells(points: np.ndarray, weights: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """geogram's regular cells of (m, d) points (d = 2 or 3, m > d) with (m,) weights:
    (t, d+1) int32 cells, each row ascending, and their (t, d+1) int32 neighbours (neighbour
    i opposite vertex i, -1 on the hull), as core.build.delaunay.regular_cells gives Qhull's;
    hidden points, and coincident points but the heaviest, are in no cell. The same input
    gives the same arrays, cell order included. Calls from several threads run one at a time.

    InputError when the points span no cell (all coplanar or collinear); GeogramError when
    geogram fails otherwise, the points are more than MAX_POINTS or the library is missing."""
    lib = _library()
    if lib is None:
        raise GeogramError("geogram's library was not built")
    m, d = points.shape
    if m > MAX_POINTS[d]:
        raise GeogramError(f"{m:,} points are more than geogram's 32-bit cell arrays take "
                           f"({MAX_POINTS[d]:,} at most in {d}D)")
    xyz = np.ascontiguousarray(points, dtype=np.float64)
    w = np.ascontiguousarray(weights, dtype=np.float64)
    if w.shape != (m,):  # the library reads m weights
        raise ValueError(f"{m} points need ({m},) weights, not {w.shape}")
    handle, count = ctypes.c_void_p(), ctypes.c_int64()
    code = lib.as_regular(d, m, xyz.ctypes.data, w.ctypes.data, ctypes.byref(handle),
                          ctypes.byref(count))
    if code == _FLAT:
        raise InputError("the points span no cell: they are (nearly) collinear or coplanar")
    if code == _NO_MEMORY:
        raise MemoryError("out of memory in geogram's regular triangulation")
    if code != 0:
        raise GeogramError(f"geogram's regular triangulation failed (code {code})")
    try:
        cells = np.empty((count.value, d + 1), dtype=np.int32)
        neighbors = np.empty((count.value, d + 1), dtype=np.int32)
    except MemoryError:
        lib.as_free(handle)
        raise
    lib.as_take(handle, cells.ctypes.data, neighbors.ctypes.data)
    return cells, neighbors

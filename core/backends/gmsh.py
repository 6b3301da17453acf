"""gmsh's Delaunay (optional, GPL: `pip install alphascoop[fast]`): 2–3× faster than Qhull.

gmsh.algorithm.tetrahedralize / triangulate return Delaunay cells without neighbours and
without some cells near the hull; core.backends.restore completes them and
core.backends.certify decides whether the result is certainly the unique Delaunay
triangulation (the one the table then gets from Qhull too). gmsh draws from the C library's
rand(), whose state one call leaves to the next: every call reseeds it first, so the same
points give the same cells (and the same choice of backend) however many calls came before.
"""

from __future__ import annotations

import ctypes
import importlib.util
import signal
import threading

import numpy as np

_lock = threading.Lock()


def installed() -> bool:
    """Whether the optional gmsh package can be imported."""
    return importlib.util.find_spec("gmsh") is not None


def _ready():
    """The gmsh module, initialised once, quietly, without touching signal handlers (so any
    thread may build)."""
    import gmsh

    if not gmsh.isInitialized():
        ignored = hasattr(signal, "SIGPIPE") and signal.getsignal(signal.SIGPIPE) == signal.SIG_IGN
        gmsh.initialize(readConfigFiles=False, interruptible=False)
        if ignored:
            _ignore_sigpipe()
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.option.setNumber("General.Verbosity", 0)
    return gmsh


def _ignore_sigpipe() -> None:
    """Ignore SIGPIPE again, as Python does: gmsh.initialize restores its default (death),
    so a write to a pipe whose reader has gone would kill this process instead of raising
    BrokenPipeError. Done in C: signal.signal may only be called from the main thread."""
    try:
        libc = ctypes.CDLL(None)
        libc.signal.argtypes = [ctypes.c_int, ctypes.c_void_p]
        libc.signal.restype = ctypes.c_void_p
        libc.signal(signal.SIGPIPE, signal.SIG_IGN.value)
    except (OSError, AttributeError):
        pass  # no C signal() to call: not a POSIX system, where SIGPIPE does not exist


#: The seed every gmsh call starts from: the C library's own at the start of a process.
RAND_SEED = 1


def _reseed(gmsh) -> None:
    """Reset the rand() state gmsh draws from (the C library's, process-wide) to RAND_SEED,
    where that library can be reached (srand found through gmsh's own library)."""
    try:
        srand = gmsh.lib.srand
    except AttributeError:
        return  # no srand beside gmsh (its C runtime not shared): calls may then differ
    srand.argtypes, srand.restype = [ctypes.c_uint], None
    srand(RAND_SEED)


def gmsh_cells(points: np.ndarray) -> np.ndarray:
    """(t, d+1) int32 cells with ascending rows that gmsh finds for (m, 2) or (m, 3)
    distinct points (a subset of the Delaunay cells; may be empty), the same for the same
    points on every call (_reseed). gmsh holds global state, so calls are serialised."""
    d = points.shape[1]
    flat = np.ascontiguousarray(points, dtype=np.float64).ravel()
    with _lock:
        gmsh = _ready()
        _reseed(gmsh)
        if d == 3:
            raw = gmsh.algorithm.tetrahedralize(flat)[0]
        else:
            raw = gmsh.algorithm.triangulate(flat)
        cells = np.asarray(raw).reshape(-1, d + 1).astype(np.int32)
    cells -= 1  # gmsh numbers points from 1
    cells.sort(axis=1)
    return cells

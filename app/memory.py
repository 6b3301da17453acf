"""The window process's memory: what it holds now (RSS) and giving freed tables back to the OS.

A big table is freed as many numpy arrays of a few megabytes. glibc's malloc raises its mmap
threshold after such frees (up to 32 MiB), so later arrays of that size come from its heaps,
and freed heap memory stays in the process: the RSS of a window that re-opens 100k-point
files climbed 0.95 -> 1.70 GiB over five opens with one dataset alive. `malloc_trim(0)` after
a dataset is released gives it back (measured flat at 0.94 / 1.02 GiB). Fixing the threshold
instead (mallopt) kept the RSS flat too but made the table's loading passes 30-50 % slower.
"""

from __future__ import annotations

import ctypes
import gc
import os
import resource
from functools import cache

STATM = "/proc/self/statm"


def rss_bytes() -> int:
    """Resident set size of this process now, in bytes (0 where /proc is missing)."""
    try:
        with open(STATM, encoding="ascii") as stream:
            resident = int(stream.read().split()[1])
    except (OSError, IndexError, ValueError):
        return 0
    return resident * os.sysconf("SC_PAGE_SIZE")


def peak_rss_bytes(children: bool = False) -> int:
    """Peak resident set size in bytes of this process (or, with `children`, of the largest
    child process it waited for, e.g. a build process)."""
    who = resource.RUSAGE_CHILDREN if children else resource.RUSAGE_SELF
    return resource.getrusage(who).ru_maxrss * 1024  # Linux reports KiB


@cache
def glibc_trim():
    """glibc's malloc_trim, or None on another C library (musl, macOS, Windows). Looked up
    among the symbols already loaded (ctypes.util.find_library would start ldconfig)."""
    try:
        function = ctypes.CDLL(None).malloc_trim
    except (OSError, AttributeError, TypeError):
        return None
    function.argtypes, function.restype = [ctypes.c_size_t], ctypes.c_int
    return function


def give_back() -> int:
    """Collect garbage, then return the allocator's free pages to the OS (glibc
    `malloc_trim(0)`, every arena); the bytes of RSS that went back (0 elsewhere).

    Call it after a dataset was released, not on a slider step: it walks every heap."""
    before = rss_bytes()
    gc.collect()
    trim = glibc_trim()
    if trim is not None:
        trim(0)
    return max(before - rss_bytes(), 0)

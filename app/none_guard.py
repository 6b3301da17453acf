"""Keep None alive however often a binding releases it: the window's exit stays clean.

PySide6/shiboken 6.12 releases None once more than it takes on some calls that return
nothing (QSlider.setValue, leaving a `with QSignalBlocker(...)` block: one reference each;
about 46 for every slider step of the window). On CPython before 3.12, where None is not
immortal, its count then falls by that much at each step; a long session brings it to zero,
and the interpreter aborts with "Fatal Python error: none_dealloc" (most often at exit,
when the last references go). Giving None a reserve of references at start makes that
unreachable: 2**40 of them outlast some 10**10 slider steps. None is never freed, so the
reserve changes nothing else.
"""

from __future__ import annotations

import ctypes
import platform
import sys

RESERVE = 1 << 40  # references added to None (a count far from any overflow: 2**63)


def needed() -> bool:
    """True where None has a reference count that can reach zero (CPython before 3.12)."""
    return platform.python_implementation() == "CPython" and sys.version_info < (3, 12)


def keep_none_alive() -> None:
    """Give None RESERVE more references, once (a second call tops up nothing: the reserve
    is still there unless 2**40 releases happened)."""
    if not needed() or sys.getrefcount(None) >= RESERVE // 2:
        return
    count = ctypes.c_ssize_t.from_address(id(None))  # ob_refcnt, PyObject's first field
    count.value += RESERVE

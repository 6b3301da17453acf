"""The body of a split gmsh triangulation's child process (core.backends.gmsh_half):
`python -m core.backends.half_child <parent pid>` reads the points on stdin and writes the
half's kept cells (core.backends.split.gmsh_half) to stdout."""

from __future__ import annotations

import ctypes
import os
import signal
import sys

from core.backends.gmsh_half import receive_arrays, send_arrays
from core.backends.split import gmsh_half
from core.errors import AlphaScoopError

PR_SET_PDEATHSIG = 1
PR_SET_NAME = 15
NAME = b"alphascoop-half"  # the command name (ps, the benchmarks' memory sampling)


def _die_with_parent(parent: int) -> None:
    """Be killed when the thread that started this process ends (Linux), named NAME; exit
    at once if the parent is gone already."""
    try:
        libc = ctypes.CDLL(None, use_errno=True)
        libc.prctl(PR_SET_PDEATHSIG, signal.SIGKILL, 0, 0, 0)
        libc.prctl(PR_SET_NAME, ctypes.c_char_p(NAME), 0, 0, 0)
    except (OSError, AttributeError):
        pass  # not Linux: the parent's stop() is all there is
    if os.getppid() != parent:
        sys.exit(1)
    signal.signal(signal.SIGINT, signal.SIG_IGN)  # Ctrl-C is the parent's to handle


def main() -> int:
    """The process's body: read the inputs, triangulate the half, write its kept cells."""
    _die_with_parent(int(sys.argv[1]))
    out = os.fdopen(os.dup(1), "wb")  # the answer's own channel: anything a library
    os.dup2(2, 1)  # prints on standard output goes to standard error instead
    try:
        fields, arrays = receive_arrays(sys.stdin.buffer)
        half = gmsh_half(arrays["points"], arrays["ids"], arrays["other"],
                         int(fields["axis"]), bool(fields["ahead"]))
    except (ValueError, KeyError, MemoryError, AlphaScoopError) as error:
        half = f"the second half failed ({type(error).__name__}: {error})"  # a reason, for
        # the parent's note and its fallback, instead of a traceback on the user's terminal
    if isinstance(half, str):
        send_arrays(out, {}, reason=half)
    else:
        send_arrays(out, {"cells": half.cells, "nbrs": half.nbrs, "mirror": half.mirror},
                    reason="")
    return 0


if __name__ == "__main__":
    sys.exit(main())

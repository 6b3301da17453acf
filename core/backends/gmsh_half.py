"""One half of a split gmsh triangulation in a process of its own (gmsh holds global state
and one core, so the two halves run in two processes: core.backends.split).

`GmshHalf.start(...)` runs `python -m core.backends.half_child` with the points on its stdin
and reads the half's kept cells back from its stdout (raw arrays behind a JSON header: no
pickle either way). The process is killed with the thread that started it
(PR_SET_PDEATHSIG on Linux; a killed build leaves no half running on), and by `stop()`.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import threading
from pathlib import Path
from typing import BinaryIO

import numpy as np

#: The only dtypes that cross the pipe (never objects).
DTYPES = ("<f8", "<i8", "<i4", "|i1", "|b1")


def send_arrays(stream: BinaryIO, arrays: dict[str, np.ndarray], **fields: object) -> None:
    """Write `fields` and the arrays' names, dtypes and shapes as one JSON line, then each
    array's bytes in that order."""
    header = {"fields": fields,
              "arrays": [[name, a.dtype.str, list(a.shape)] for name, a in arrays.items()]}
    stream.write(json.dumps(header).encode() + b"\n")
    for a in arrays.values():
        if a.size:
            stream.write(np.ascontiguousarray(a).reshape(-1).view(np.uint8))
    stream.flush()


def receive_arrays(stream: BinaryIO) -> tuple[dict, dict[str, np.ndarray]]:
    """(fields, arrays) that send_arrays wrote; ValueError on a truncated or malformed
    stream or a dtype outside DTYPES."""
    line = stream.readline(1 << 16)
    if not line.endswith(b"\n"):
        raise ValueError("no header")
    try:
        header = json.loads(line)
        fields, listed = dict(header["fields"]), [
            (str(name), str(dtype), tuple(int(s) for s in shape))
            for name, dtype, shape in header["arrays"]]
    except (KeyError, TypeError) as error:
        raise ValueError(f"a malformed header ({error})") from None
    arrays = {}
    for name, dtype, shape in listed:
        if dtype not in DTYPES or any(s < 0 for s in shape):
            raise ValueError(f"unexpected array {dtype} {shape}")
        out = np.empty(shape, dtype=np.dtype(dtype))
        view = memoryview(out.reshape(-1).view(np.uint8))
        done = 0
        while done < len(view):
            got = stream.readinto(view[done:])
            if not got:
                raise ValueError("the stream ended inside an array")
            done += got
        arrays[name] = out
    return fields, arrays


class GmshHalf:
    """A half triangulated in a child process: start, then result() or stop()."""

    def __init__(self, process: subprocess.Popen, writer: threading.Thread) -> None:
        self._process, self._writer = process, writer

    @classmethod
    def start(cls, points: np.ndarray, ids: np.ndarray, other: np.ndarray, axis: int,
              ahead: bool) -> GmshHalf:
        """Start triangulating points[ids] (core.backends.split.gmsh_half) in a new
        process; the points are written to it from a thread, so this returns at once.
        OSError when the process cannot start."""
        if not sys.executable:
            raise OSError("no Python executable to run it with")
        root = str(Path(__file__).resolve().parents[2])  # the folder holding `core`
        env = dict(os.environ)
        env["PYTHONPATH"] = os.pathsep.join(filter(None, (root, env.get("PYTHONPATH"))))
        process = subprocess.Popen(
            [sys.executable, "-m", "core.backends.half_child", str(os.getpid())],
            stdin=subprocess.PIPE, stdout=subprocess.PIPE, env=env, close_fds=True)

        def write() -> None:
            try:
                with process.stdin:
                    send_arrays(process.stdin, {"points": points, "ids": ids, "other": other},
                                axis=axis, ahead=ahead)
            except (OSError, ValueError):
                pass  # it died: result() says so

        writer = threading.Thread(target=write, name="alphascoop-gmsh-half-input", daemon=True)
        writer.start()
        return cls(process, writer)

    def result(self) -> dict[str, np.ndarray] | str:
        """The half's arrays ("cells", "nbrs", "mirror": its kept cells, split.gmsh_half), or
        why there are none (its own reason, or that the process failed)."""
        try:
            fields, arrays = receive_arrays(self._process.stdout)
        except (OSError, ValueError) as error:
            self.stop()
            return f"the second half's process failed ({error})"
        self._process.stdout.close()
        self._writer.join()
        code = self._process.wait()
        if code != 0:
            return f"the second half's process failed (exit code {code})"
        return str(fields["reason"]) if fields.get("reason") else arrays

    def stop(self) -> None:
        """Kill the process (if it still runs) and reap it."""
        if self._process.poll() is None:
            self._process.kill()
        self._process.wait()
        self._writer.join()
        self._process.stdout.close()

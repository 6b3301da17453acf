"""The peak memory of this process's children (the window's build and topology processes, and
the build's gmsh half process), sampled from a thread without ever waiting for them.

The children are found in /proc (their parent pid), not through multiprocessing: its
`active_children()` reaps the children that have exited, which races with the thread that
owns them (its `join` then finds no child to wait for). A child is named by its command
name, which app.child_process sets to the first 15 characters of the process's name.
"""

from __future__ import annotations

import os
import threading

SAMPLE_S = 0.1  # how often the children's peak memory is read
COMM_CHARS = 15  # Linux keeps this many characters of a process's command name
NAMES = ("alphascoop-build", "alphascoop-topology")  # app/build_process, app/topology_process
HALF = "alphascoop-half"  # a build's second gmsh half (core/backends/half_child.py)


def child_processes(parent: int | None = None) -> dict[int, str]:
    """{pid: command name} of parent's (default: this process's) living or exited but not yet
    waited-for children, read from /proc/<pid>/stat; nothing is waited for."""
    parent = os.getpid() if parent is None else parent
    found = {}
    for entry in os.scandir("/proc"):
        if not entry.name.isdigit():
            continue
        try:
            with open(f"/proc/{entry.name}/stat", encoding="utf-8", errors="replace") as handle:
                stat = handle.read()
        except OSError:  # it ended meanwhile
            continue
        comm, _, rest = stat.partition("(")[2].rpartition(")")
        fields = rest.split()  # state, ppid, ...
        if len(fields) > 1 and fields[1] == str(parent):
            found[int(entry.name)] = comm
    return found


def passes(names: tuple[str, ...] = NAMES, parent: int | None = None) -> dict[int, str]:
    """{pid: name} of parent's children whose command name starts one of `names` (the build
    and topology processes; not multiprocessing's resource tracker, for one), and their own
    children named HALF (a build's second gmsh half)."""
    short = {name[:COMM_CHARS]: name for name in names}
    found = {pid: short[comm] for pid, comm in child_processes(parent).items()
             if comm in short}
    for pid in list(found):  # a build's own child: its second gmsh half
        found.update({half: HALF for half, comm in child_processes(pid).items()
                      if comm == HALF[:COMM_CHARS]})
    return found


def cpu_seconds_of(pid: int) -> float:
    """A process's CPU seconds so far (user + system, /proc/<pid>/stat), its waited-for
    children's included (a build's gmsh half); 0 when it is gone."""
    try:
        with open(f"/proc/{pid}/stat", encoding="utf-8", errors="replace") as handle:
            fields = handle.read().rpartition(")")[2].split()  # state is field 3: index 0
        return sum(int(f) for f in fields[11:15]) / os.sysconf("SC_CLK_TCK")
    except (OSError, ValueError, IndexError):
        return 0.0


def vm_hwm_mib(pid: int) -> float:
    """A process's peak resident set in MiB (VmHWM: it starts afresh at exec, unlike
    ru_maxrss); 0 when it is gone or has exited."""
    try:
        with open(f"/proc/{pid}/status", encoding="ascii") as handle:
            for line in handle:
                if line.startswith("VmHWM:"):
                    return int(line.split()[1]) / 1024.0
    except (OSError, ValueError):
        pass
    return 0.0


class ChildPeaks:
    """Samples this process's children named in `names` (see `passes`) every SAMPLE_S from a
    thread: each one's own peak resident set, by name."""

    def __init__(self, names: tuple[str, ...] = NAMES) -> None:
        """Start sampling now."""
        self.names = names
        self.peaks: dict[str, float] = {}
        self.sweeps = 0  # samples taken so far
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._run, daemon=True)
        self._thread.start()

    def _run(self) -> None:
        while not self._stop.wait(SAMPLE_S):
            for pid, name in passes(self.names).items():
                peak = vm_hwm_mib(pid)
                if peak:
                    self.peaks[name] = max(self.peaks.get(name, 0.0), peak)
            self.sweeps += 1

    def stop(self) -> dict[str, float]:
        """Stop sampling; {child process name: peak MiB}."""
        self._stop.set()
        self._thread.join()
        return dict(self.peaks)

"""ChildPeaks (benchmarks/child_peaks.py): a child's own peak memory by its name, read from a
thread that never waits for (reaps) the children it samples."""

from __future__ import annotations

import multiprocessing
import subprocess
import sys
import time
from collections.abc import Callable

from child_peaks import SAMPLE_S, ChildPeaks, child_processes, cpu_seconds_of, passes

LIVENESS_S = 60.0  # generous bound for a child to start, allocate or exit; never a timing
BLOCK_MIB = 64
ALLOCATING_CHILD = f"""
import sys
open("/proc/self/comm", "w").write("alphascoop-topology"[:15])
block = bytes(range(256)) * ({BLOCK_MIB} << 12)  # {BLOCK_MIB} MiB, every page written
print("ready", flush=True)
sys.stdin.read()
"""


def wait_for(condition: Callable[[], bool]) -> None:
    """Poll condition until it holds (fail after LIVENESS_S)."""
    deadline = time.monotonic() + LIVENESS_S
    while not condition():
        assert time.monotonic() < deadline, "not within the liveness bound"
        time.sleep(SAMPLE_S / 2)


def state(pid: int) -> str | None:
    """The process's state letter (Z: exited, not yet waited for); None once it is gone."""
    try:
        with open(f"/proc/{pid}/stat", encoding="utf-8") as handle:
            return handle.read().rpartition(")")[2].split()[0]
    except OSError:
        return None


def test_a_childs_peak_is_read_by_its_full_name():
    peaks = ChildPeaks()
    child = subprocess.Popen([sys.executable, "-c", ALLOCATING_CHILD], stdin=subprocess.PIPE,
                             stdout=subprocess.PIPE, text=True)
    try:
        assert child.stdout.readline().strip() == "ready"
        assert child_processes()[child.pid] == "alphascoop-topo"
        assert passes()[child.pid] == "alphascoop-topology"
        wait_for(lambda: peaks.peaks.get("alphascoop-topology", 0.0) >= BLOCK_MIB)
    finally:
        child.stdin.close()
        child.wait(LIVENESS_S)
        child.stdout.close()
    found = peaks.stop()
    assert list(found) == ["alphascoop-topology"] and found["alphascoop-topology"] >= BLOCK_MIB


def test_an_exited_child_is_left_for_its_owner_to_wait_for():
    child = multiprocessing.get_context("spawn").Process(target=time.sleep, args=(3.0,))
    child.start()
    name = child_processes()[child.pid]  # the interpreter's, as the child sets none
    peaks = ChildPeaks(names=(name,))
    wait_for(lambda: name in peaks.peaks)  # sampled while it runs
    wait_for(lambda: state(child.pid) == "Z")  # exited; only its owner may reap it
    seen = peaks.sweeps
    wait_for(lambda: peaks.sweeps >= seen + 3)  # the sampler has looked at it meanwhile
    assert state(child.pid) == "Z" and child.pid in child_processes()
    child.join(LIVENESS_S)
    assert child.exitcode == 0 and state(child.pid) is None
    peaks.stop()


def test_a_running_childs_cpu_seconds_are_read_from_proc():
    """The CPU a child spent so far, read while it runs (not yet in RUSAGE_CHILDREN): its
    own figure (time.process_time in the child) within the clock's tick; 0 once it is gone."""
    busy = ("import time\nend = time.process_time() + 0.3\nwhile time.process_time() < end:"
            "\n    pass\nprint(time.process_time(), flush=True)\ninput()\n")
    child = subprocess.Popen([sys.executable, "-c", busy], stdin=subprocess.PIPE,
                             stdout=subprocess.PIPE, text=True)
    try:
        own = float(child.stdout.readline())
        read = cpu_seconds_of(child.pid)
        assert abs(read - own) <= 0.05 and read >= 0.3 - 0.02
    finally:
        child.communicate("\n")
    assert cpu_seconds_of(child.pid) == 0.0


HALF_PARENT = """
import subprocess, sys
open("/proc/self/comm", "w").write("alphascoop-build"[:15])
half = subprocess.Popen([sys.executable, "-c", {child!r}], stdin=subprocess.PIPE,
                        stdout=subprocess.PIPE, text=True)
print(half.pid, half.stdout.readline().strip(), flush=True)
sys.stdin.read()
half.stdin.close()
half.wait()
"""
HALF_CHILD = ALLOCATING_CHILD.replace('"alphascoop-topology"', '"alphascoop-half"')


def test_a_builds_gmsh_half_is_sampled_by_its_name():
    """The build's own child named alphascoop-half (core/backends/half_child.py) is found and
    sampled apart: its peak is not the build's."""
    peaks = ChildPeaks()
    build = subprocess.Popen([sys.executable, "-c", HALF_PARENT.format(child=HALF_CHILD)],
                             stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True)
    try:
        half, ready = build.stdout.readline().split()
        assert ready == "ready"
        assert passes()[build.pid] == "alphascoop-build"
        assert passes()[int(half)] == "alphascoop-half"
        wait_for(lambda: peaks.peaks.get("alphascoop-half", 0.0) >= BLOCK_MIB)
    finally:
        build.stdin.close()
        build.wait(LIVENESS_S)
        build.stdout.close()
    found = peaks.stop()
    assert found["alphascoop-half"] >= BLOCK_MIB
    assert found["alphascoop-build"] < found["alphascoop-half"]

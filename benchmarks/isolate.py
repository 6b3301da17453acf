"""Run one measurement in a fresh interpreter so its peak memory is its own."""

from __future__ import annotations

import argparse
import multiprocessing as mp
import os
import resource
import time
import traceback
from collections.abc import Callable
from itertools import pairwise
from typing import Any

MIB = 1024.0 * 1024.0


def rss_mib() -> float:
    """Current resident set size of this process, MiB (Linux /proc/self/statm)."""
    with open("/proc/self/statm") as handle:
        pages = int(handle.read().split()[1])
    return pages * os.sysconf("SC_PAGE_SIZE") / MIB


def peak_rss_mib() -> float:
    """Peak resident set size of this process so far, MiB (ru_maxrss is KiB on Linux)."""
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0


class Probe:
    """Wall time, CPU time and memory of one operation; the baseline is taken at creation."""

    def __init__(self) -> None:
        self.base_rss = rss_mib()
        self.base_peak = peak_rss_mib()
        self._wall = time.perf_counter()
        self._cpu = time.process_time() + _children_cpu()

    def result(self, **extra: Any) -> dict:
        """Figures since creation: seconds, cpu_seconds (the waited-for children's included:
        a gmsh build's second half), peak_mib (whole process), extra_mib, children_peak_mib
        (the largest waited-for child's peak, 0 without one)."""
        wall = time.perf_counter() - self._wall
        peak = peak_rss_mib()
        return {
            "seconds": wall,
            "cpu_seconds": time.process_time() + _children_cpu() - self._cpu,
            "base_rss_mib": self.base_rss,
            "base_peak_mib": self.base_peak,
            "peak_mib": peak,
            "extra_mib": peak - self.base_rss,
            "children_peak_mib": resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024.0,
            **extra,
        }


def _children_cpu() -> float:
    """CPU seconds of this process's waited-for children so far."""
    children = resource.getrusage(resource.RUSAGE_CHILDREN)
    return children.ru_utime + children.ru_stime


class StageClock:
    """A build's progress(fraction, stage) callback that times each stage, wall and CPU,
    from its call to the next one's (the last stage ends at `stages()`)."""

    def __init__(self) -> None:
        self.marks: list[tuple[float, float, str]] = []

    def __call__(self, _fraction: float, stage: str) -> None:
        self.marks.append((time.perf_counter(), time.process_time(), stage))

    def stages(self) -> list[dict]:
        """[{stage, seconds, cpu_seconds}] of the stages reported so far, ending now."""
        self.marks.append((time.perf_counter(), time.process_time(), ""))
        return [{"stage": stage, "seconds": t1 - t0, "cpu_seconds": c1 - c0}
                for (t0, c0, stage), (t1, c1, _) in pairwise(self.marks)]


def best_of(fn: Callable[[], Any], reps: int) -> tuple[float, float, Any]:
    """Fastest wall and CPU time (all threads) of reps calls of fn, seconds; last return value."""
    wall = cpu = float("inf")
    value = None
    for _ in range(max(1, reps)):
        start, start_cpu = time.perf_counter(), time.process_time()
        value = fn()
        cpu = min(cpu, time.process_time() - start_cpu)
        wall = min(wall, time.perf_counter() - start)
    return wall, cpu, value


def _child(conn: Any, fn: Callable[..., dict], args: tuple) -> None:
    """Child entry point: send fn(*args), or {'error': message} when it raises."""
    try:
        result = fn(*args)
    except Exception as exc:  # reported to the parent as a figure that could not be measured
        result = {"error": f"{type(exc).__name__}: {exc}", "trace": traceback.format_exc()}
    conn.send(result)
    conn.close()


def run_isolated(fn: Callable[..., dict], *args: Any) -> dict:
    """fn(*args) run in a new 'spawn' process; its dict, or {'error': ...} if it failed or died."""
    ctx = mp.get_context("spawn")
    receiver, sender = ctx.Pipe(duplex=False)
    proc = ctx.Process(target=_child, args=(sender, fn, args))
    proc.start()
    sender.close()
    try:
        result = receiver.recv()
    except EOFError:
        result = None
    proc.join()
    if result is None:
        code = proc.exitcode
        why = " (killed: out of memory?)" if code is not None and code < 0 else ""
        result = {"error": f"measurement process died with exit code {code}{why}"}
    return result


def size_options(doc: str, n: int, what: str = "points") -> argparse.ArgumentParser:
    """A benchmark's parser with the options every size-driven benchmark shares: --n (how
    many `what`, default n), --seed and --json; the script adds its own."""
    parser = argparse.ArgumentParser(description=doc.splitlines()[0])
    parser.add_argument("--n", type=int, default=n, help=f"{what} (default {n})")
    parser.add_argument("--seed", type=int, default=0, help="sample seed")
    parser.add_argument("--json", metavar="PATH", help="also write the figures as JSON")
    return parser

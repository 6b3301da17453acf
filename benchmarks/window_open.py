"""Measurements in a real window (run in a fresh process under Xvfb): first open and a soak.

`first_open` opens a file in a new MainWindow with an empty table cache, as a user's first
open is: file -> slider live (the model has the dataset: the slider moves shapes) -> topology
done (signatures and optimal alpha; the same moment when the window waits for them), with the
longest GUI-thread stall in between (a 10 ms QTimer probe) and the build and topology
processes' own peaks (sampled VmHWM, benchmarks/child_peaks.py). With
`soak`, the same window then opens and cancels the file 10 times and opens the two files
alternately 10 times; the process RSS is read after each outcome.
"""

from __future__ import annotations

import os
import resource
import sys
import tempfile
import time

from child_peaks import ChildPeaks, cpu_seconds_of, passes
from isolate import MIB, peak_rss_mib, rss_mib

TIMEOUT_MS = 3_600_000
CANCELS, REOPENS = 10, 10
CANCEL_AFTER_S = 2.0  # cancel once the build has run this long (the child is started)
PROBE_MS = 10  # the stall probe's tick
PROCESS_END_SECONDS = 300  # the topology process's cache rewrite ends well before (7 s at 1M)
DRAG_STEPS = 200  # critical values a probe's drag walks over
ARRIVAL_MS = 2000  # the probe runs on this long after the topology arrived: the docks' and
# the view's deferred redraws (matplotlib's draw_idle, the render at the opening alpha) count


def _wait(signal, timeout_ms: int = TIMEOUT_MS) -> tuple:
    """Run the Qt event loop until signal fires; its arguments (TimeoutError if it never)."""
    from PySide6.QtCore import QEventLoop, QTimer

    loop, got = QEventLoop(), []

    def done(*args) -> None:
        got.append(args)
        loop.quit()

    signal.connect(done)
    QTimer.singleShot(timeout_ms, loop.quit)
    loop.exec()
    signal.disconnect(done)
    if not got:
        raise TimeoutError("the window did not answer in time")
    return got[0]


def _spin(ms: int) -> None:
    """Process Qt events for ms milliseconds."""
    from PySide6.QtCore import QEventLoop, QTimer

    loop = QEventLoop()
    QTimer.singleShot(ms, loop.quit)
    loop.exec()


def _window(folder: str):
    """A shown MainWindow with private settings (the QApplication is made once)."""
    os.environ["QT_API"] = "pyside6"
    from PySide6.QtCore import QSettings
    from PySide6.QtWidgets import QApplication

    from app.main_window import MainWindow

    app = QApplication.instance() or QApplication([])
    win = MainWindow(QSettings(os.path.join(folder, "settings.ini"),
                               QSettings.Format.IniFormat))
    win.resize(1280, 800)
    win.show()
    app.processEvents()
    return win


def _topology_signal(win):
    """The model's 'topology done' signal when the window hands the dataset over before its
    topology, else None (the dataset comes with it)."""
    return getattr(win.model, "topologyChanged", None)


class StallProbe:
    """A QTimer that ticks every PROBE_MS on the GUI thread: a gap between two ticks beyond
    PROBE_MS is a time the GUI thread could not answer (a slider drag froze that long)."""

    def __init__(self) -> None:
        from PySide6.QtCore import QTimer

        self.timer = QTimer()
        self.timer.setInterval(PROBE_MS)
        self.timer.timeout.connect(self._tick)
        self.last = 0.0
        self.gaps: list[tuple[float, float]] = []  # (when the gap ended, its stall seconds)
        self.steps: list[tuple[float, float]] = []  # (when a drag step ended, its seconds)
        self.drag = None

    def start(self, drag=None) -> None:
        """Start measuring now; with `drag` (a function called on every tick: a slider step's
        query) its durations are recorded too."""
        self.last, self.gaps, self.steps, self.drag = time.perf_counter(), [], [], drag
        self.timer.start()

    def _tick(self) -> None:
        now = time.perf_counter()
        self.gaps.append((now, max(now - self.last - PROBE_MS / 1000, 0.0)))
        if self.drag is not None:
            self.drag()
            self.steps.append((time.perf_counter(), time.perf_counter() - now))
        self.last = time.perf_counter()

    def longest_step(self, until: float = float("inf")) -> float:
        """The longest drag step (seconds) among those that ended by `until`."""
        return max((step for end, step in self.steps if end <= until), default=0.0)

    def stop(self) -> None:
        """Stop measuring."""
        self._tick()
        self.timer.stop()

    def longest(self, until: float = float("inf")) -> float:
        """The longest stall (seconds) among the gaps that ended by `until` (perf_counter)."""
        return max((gap for end, gap in self.gaps if end <= until), default=0.0)


def _cpu_seconds() -> float:
    """CPU seconds so far of this process (all threads), of its waited-for children (the
    build processes) and of its build and topology processes still running (the topology
    process goes on rewriting the cache entry after it handed its topology over)."""
    # a process reaped between these two reads would count twice (a microseconds' window)
    running = sum(cpu_seconds_of(pid) for pid in passes())
    children = resource.getrusage(resource.RUSAGE_CHILDREN)
    return time.process_time() + children.ru_utime + children.ru_stime + running


def _dragging(model):
    """A slider drag's queries without their renders: each call moves a cursor of its own
    one critical value, back and forth over DRAG_STEPS values below the opening alpha."""
    ds = model.dataset
    cursor, spectrum, start = ds.ac.cursor(), ds.spectrum, model.index
    state = {"at": start, "way": -1}

    def step() -> None:
        if not start - DRAG_STEPS < state["at"] + state["way"] <= start:
            state["way"] = -state["way"]
        state["at"] += state["way"]
        cursor.move(alpha=float(spectrum[max(state["at"], 0)]))

    return step


def _say(text: str) -> None:
    """A progress line on stderr (a run stopped by a timeout still shows how far it got)."""
    print(f"    window: {text}", file=sys.stderr, flush=True)


def _open_timed(win, path: str, drag: bool = False) -> dict:
    """Open path; seconds (wall, and CPU of this process and its build process) until the
    slider is live and until the topology is done."""
    topology = _topology_signal(win)
    stamps: dict[str, tuple[float, float]] = {}

    def stamp(name: str) -> None:
        stamps.setdefault(name, (time.perf_counter(), _cpu_seconds()))

    probe = StallProbe()
    if topology is not None:
        topology.connect(lambda *_: stamp("topology"))
    stamp("start")
    win.open_path(path)
    _wait(win.model.datasetChanged)
    stamp("live")
    _say(f"slider live after {stamps['live'][0] - stamps['start'][0]:.1f} s")
    _spin(0)  # the first frame is requested; let the event loop run once
    stamp("frame")  # the event loop is free again: the first frame of the shape is drawn
    probe.start(_dragging(win.model) if drag else None)
    if topology is not None and "topology" not in stamps and not win.model.dataset.has_topology:
        _wait(topology)
    if topology is not None:
        _say(f"topology done after {time.perf_counter() - stamps['start'][0]:.1f} s")
        _spin(ARRIVAL_MS)
    probe.stop()
    ds = win.model.dataset
    info = getattr(ds.ac, "build_info", None)
    (start, start_cpu), (live, live_cpu) = stamps["start"], stamps["live"]
    done, done_cpu = stamps.get("topology", stamps["live"])
    frame, frame_cpu = stamps["frame"]
    return {"live_seconds": live - start, "live_cpu_seconds": live_cpu - start_cpu,
            "frame_seconds": frame - start, "frame_cpu_seconds": frame_cpu - start_cpu,
            "topology_seconds": done - start, "topology_cpu_seconds": done_cpu - start_cpu,
            # while the topology computes (the docks filling in when it arrives apart)
            "longest_stall_seconds": probe.longest(stamps.get("topology", (0.0,))[0]),
            "longest_stall_with_arrival_seconds": probe.longest(),
            "longest_step_seconds": probe.longest_step(stamps.get("topology", (0.0,))[0]),
            "backend": getattr(info, "backend", "qhull"),
            "cells": len(ds.ac.simplices(ds.ac.dim)), "points": len(ds.ac.points)}


def first_open(points_path: str, other_path: str, cancel_path: str, soak: int,
               topology_in_thread: bool = False, drag: bool = False) -> dict:
    """First open of points_path in a new window (empty cache): times, peaks, the longest
    GUI-thread stall while the topology completes, and with `soak` (a count of cycles; True
    = CANCELS and REOPENS) the RSS after that many cancelled opens of cancel_path and re-opens
    of points_path / other_path. `topology_in_thread` runs the topology pass in a thread of
    the window (as small sets do), for comparison; `drag` has the stall probe step a cursor
    on every tick (a slider drag's queries) while the topology computes."""
    from app import memory, topology_process

    if topology_in_thread:
        topology_process.IN_THREAD_BELOW = 2**62
    with tempfile.TemporaryDirectory(prefix="alphascoop-first-open-") as folder:
        os.environ["ALPHASCOOP_CACHE_DIR"] = os.path.join(folder, "cache")
        win = _window(folder)
        base = rss_mib()
        children = ChildPeaks()
        result = _open_timed(win, points_path, drag)
        win.topology.wait()
        deadline = time.perf_counter() + PROCESS_END_SECONDS
        while passes() and time.perf_counter() < deadline:  # the topology process's rewrite
            _spin(100)
        if passes():
            raise RuntimeError(f"a build or topology process still runs "
                               f"{PROCESS_END_SECONDS} s after the topology arrived")
        _spin(200)  # the deferred give-back runs
        peaks = children.stop()
        result.update(base_rss_mib=base, rss_after_mib=rss_mib(), peak_mib=peak_rss_mib(),
                      child_peak_mib=max(peaks.values(), default=0.0),
                      child_peaks_mib=peaks,
                      child_maxrss_mib=memory.peak_rss_bytes(children=True) / MIB)
        if soak:
            cycles = (CANCELS, REOPENS) if soak is True else (int(soak), int(soak))
            result["soak"] = _soak(win, points_path, other_path, cancel_path, *cycles)
        win.close()
    return result


def _soak(win, first: str, second: str, cancel: str, cancels: int = CANCELS,
          reopens: int = REOPENS) -> dict:
    """Open/cancel `cancel` `cancels` times (its build never finishes, so each one starts the
    build process), then `reopens` alternate opens (second first); RSS in MiB
    after each, the seconds of each re-open, and the old datasets still alive at the end."""
    import gc
    import weakref

    cancelled, reopened, seconds, alive = [], [], [], []
    for _ in range(cancels):
        win.open_path(cancel)
        _spin(int(CANCEL_AFTER_S * 1000))
        win.loader.cancel()
        while win.loader.is_busy():
            _spin(50)
        _spin(200)
        cancelled.append(rss_mib())
    left = len(passes())  # read from /proc: nothing is reaped under the loader's join
    for i in range(reopens):
        start = time.perf_counter()
        win.open_path(second if i % 2 == 0 else first)
        _wait(win.model.datasetChanged)
        seconds.append(time.perf_counter() - start)
        topology = _topology_signal(win)
        while topology is not None and (win.loader.is_busy() or win.topology.is_busy()):
            _spin(50)
        _spin(200)
        alive.append(weakref.ref(win.model.dataset))
        reopened.append(rss_mib())
    gc.collect()
    return {"after_cancel_mib": cancelled, "after_open_mib": reopened, "open_seconds": seconds,
            "build_processes_left": left,
            "old_datasets_alive": sum(ref() is not None for ref in alive[:-1]),
            "peak_mib": peak_rss_mib()}

"""Memory in the window: a soak of cancelled opens and re-opens stays flat.

One window opens a torus scan and cancels it 10 times, then opens a torus and a cube
alternately 5 times each (the first of each built in the build process, the rest read from
the table cache). The process RSS after every re-open (and its topology, from the topology
process) stays within 1.2x of its value after the first, every old dataset is released, and
no build process is left behind.
"""

from __future__ import annotations

import gc
import multiprocessing
import os
import subprocess
import sys
import weakref
from pathlib import Path

import numpy as np
import pytest
from conftest import BUILD_TIMEOUT_MS

from app import build_process, memory

N_POINTS = 60_000  # above build_process.IN_THREAD_BELOW: builds run in the child process
CANCELS, REOPENS = 10, 10
MAX_GROWTH = 1.2
SETTLE_MS = 200  # lets the window's deferred give-back run after each outcome

pytestmark = [pytest.mark.gui, pytest.mark.slow]


def torus(n: int, seed: int = 0) -> np.ndarray:
    """(n, 3) noisy torus surface sample (R = 1, r = 0.35), a scan-like shell."""
    rng = np.random.default_rng(seed)
    u, v = rng.uniform(0.0, 2.0 * np.pi, (2, n))
    tube = 0.35 + rng.normal(0.0, 0.001, n)
    ring = 1.0 + tube * np.cos(v)
    return np.column_stack((ring * np.cos(u), ring * np.sin(u), tube * np.sin(v)))


def cube(n: int, seed: int = 1) -> np.ndarray:
    """(n, 3) uniform points in the unit cube: a solid, about 6.5 cells per point."""
    return np.random.default_rng(seed).random((n, 3))


@pytest.fixture
def two_files(tmp_path):
    """A torus and a cube of N_POINTS points each, as .npy files."""
    assert N_POINTS >= build_process.IN_THREAD_BELOW
    paths = tmp_path / "torus.npy", tmp_path / "cube.npy"
    np.save(paths[0], torus(N_POINTS))
    np.save(paths[1], cube(N_POINTS))
    return paths


def shared_mappings(but: frozenset[str] = frozenset()) -> list[str]:
    """This process's mappings of tables handed over in shared memory (app.shared_folder),
    but those of the folders in `but`, as the folder of each."""
    folders = (line.partition(" /")[2].rpartition("/")[0]
               for line in Path("/proc/self/maps").read_text().splitlines()
               if "/alphascoop-shared-" in line)
    return [f"/{folder}" for folder in folders if f"/{folder}" not in but]


def open_then_cancel(qtbot, window, path) -> None:
    """Open path, cancel once the build has reported progress, wait for the cancellation."""
    with qtbot.waitSignal(window.loader.progress, timeout=BUILD_TIMEOUT_MS):
        window.open_path(path)
    with qtbot.waitSignal(window.loader.cancelled, timeout=BUILD_TIMEOUT_MS):
        window.loader.cancel()
    qtbot.waitUntil(lambda: not window.loader.is_busy(), timeout=BUILD_TIMEOUT_MS)


def test_cancelled_opens_and_reopens_keep_memory_flat(window, qtbot, two_files) -> None:
    """10 cancelled opens leave no build process; then 10 alternate re-opens: RSS after
    each within MAX_GROWTH of the first, and only the shown dataset is alive."""
    for _ in range(CANCELS):
        open_then_cancel(qtbot, window, two_files[0])
        assert window.model.dataset is None
    qtbot.waitUntil(lambda: not multiprocessing.active_children(), timeout=5_000)
    resident, alive, shared = [], [], []
    earlier = frozenset(shared_mappings())  # tables other tests' objects still hold
    for i in range(REOPENS):
        with qtbot.waitSignal(window.model.datasetChanged, timeout=BUILD_TIMEOUT_MS):
            window.open_path(two_files[i % 2])
        qtbot.waitUntil(lambda: not window.topology.is_busy(), timeout=BUILD_TIMEOUT_MS)
        qtbot.wait(SETTLE_MS)
        alive.append(weakref.ref(window.model.dataset))
        resident.append(memory.rss_bytes())
        shared.append(len(shared_mappings(earlier)))
    gc.collect()  # no build or topology process left (the last may still rewrite its entry)
    qtbot.waitUntil(lambda: not multiprocessing.active_children(), timeout=BUILD_TIMEOUT_MS)
    assert [ref() is not None for ref in alive] == [False] * (REOPENS - 1) + [True]
    # the first torus and cube came through shared memory; their mappings went with them
    assert shared[0] > 0 and shared[1] > 0 and shared[-1] == 0 and shared_mappings(earlier) == []
    growth = max(resident) / resident[0]
    figures = ", ".join(f"{r / 2**20:.0f}" for r in resident)
    assert growth <= MAX_GROWTH, f"RSS grew {growth:.2f}x over the re-opens (MiB: {figures})"


def test_rss_is_read() -> None:
    """rss_bytes reads a plausible figure: more than 10 MiB, at most the peak."""
    assert 10 * 2**20 < memory.rss_bytes() <= memory.peak_rss_bytes() * 1.05


HEAP_HOLES = """
import gc, numpy as np
from app import memory
warm = np.ones(2**19)  # one 4 MiB mmapped chunk freed: glibc raises its mmap threshold
del warm
blocks, pins = [], []
for _ in range(200):  # 200 x 2 MiB now from the heap, each followed by a live small chunk
    blocks.append(np.ones(2**18))
    pins.append(np.ones(64))
del blocks
gc.collect()
kept = memory.rss_bytes()
memory.give_back()
print(kept, memory.rss_bytes())
"""


@pytest.mark.skipif(memory.glibc_trim() is None, reason="malloc_trim is glibc's")
def test_give_back_returns_freed_heap_memory() -> None:
    """Freed 2 MiB arrays between live small ones (heap holes) stay in the process until
    give_back returns them (in a fresh interpreter, whose heap has no older holes)."""
    root = Path(__file__).resolve().parents[1]
    environ = {k: v for k, v in os.environ.items() if not k.startswith("MALLOC_")}  # defaults
    done = subprocess.run([sys.executable, "-c", HEAP_HOLES], capture_output=True, text=True,
                          check=True, cwd=root, env={**environ, "PYTHONPATH": str(root)})
    kept, after = (int(word) for word in done.stdout.split())
    assert kept > 200 * 2**20 and after < kept - 200 * 2**20

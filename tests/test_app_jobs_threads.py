"""The runner's jobs run in a Python thread that lives as long as the runner: libraries that
keep per-thread state through Python (pyproj's PROJ contexts) see one thread, not a native
thread whose Python state is made and dropped around each job, which crashed pyproj 3.7
(a CRS parsed by a second job in the same pool thread: a segmentation fault)."""

from __future__ import annotations

import threading

import pytest
from reference import DATA_ABSENT, data_dir


@pytest.mark.gui
def test_a_las_file_with_its_crs_opens_twice(window, qtbot):
    """The second read of autzen_trim.las's CRS records, in the runner's thread, crashed
    inside PROJ when that thread was a Qt pool thread."""
    from app.import_dialog import ImportOptions

    folder = data_dir()
    if folder is None:
        pytest.skip(DATA_ABSENT)
    for _ in range(2):
        with qtbot.waitSignal(window.model.datasetChanged, timeout=120_000):
            window.open_path(folder / "autzen_trim.las", ImportOptions(subsample=4000))
    assert window.model.dataset.report.n_points <= 4000


@pytest.mark.gui
def test_every_job_runs_in_one_python_thread(qtbot):
    from app.jobs import Job, Runner

    runner = Runner()
    seen = []
    for _ in range(2):
        with qtbot.waitSignal(runner.finished, timeout=10_000):
            runner.start(Job("where", lambda progress, cancel: seen.append(
                (threading.current_thread().ident, threading.current_thread().name))))
    assert seen[0] == seen[1] and not seen[0][1].startswith("Dummy")
    assert runner.wait(1000) and not runner.is_busy()


LEFT_BEHIND = """
import os, time
os.environ["QT_QPA_PLATFORM"] = "offscreen"
from PySide6.QtCore import QCoreApplication
from app.jobs import Job, Runner

app = QCoreApplication([])
runner = Runner()
runner.start(Job("stuck", lambda progress, cancel: time.sleep(60)))  # ignores Cancel
print(runner.shut_down(200))
"""


def test_a_job_that_ignores_cancel_does_not_hold_the_exit():
    """Closing leaves a stuck job behind (CLOSE_WAIT_MS): the process still exits."""
    import os
    import subprocess
    import sys
    import time
    from pathlib import Path

    root = Path(__file__).resolve().parents[1]
    start = time.monotonic()
    done = subprocess.run([sys.executable, "-c", LEFT_BEHIND], capture_output=True, text=True,
                          cwd=root, env={**os.environ, "PYTHONPATH": str(root)}, timeout=120)
    assert done.returncode == 0, done.stderr[-1500:]
    assert done.stdout.strip() == "False" and time.monotonic() - start < 40

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

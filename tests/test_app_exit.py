"""The window exits cleanly after a long session: no 'Fatal Python error: none_dealloc'.

PySide6 6.12 releases None once too often on some calls (QSlider.setValue, leaving a
QSignalBlocker block): the window's slider steps drain None's reference count, which on
CPython 3.11 ends in an abort. The window run in a child process is stepped, then the
slider is moved as often as hours of use would move it, then quit: the exit status must be
0 and standard error free of fatal errors.
"""

from __future__ import annotations

import os
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

from app.resources import SAMPLE_PATH

SCRIPT = textwrap.dedent("""
    import os, sys
    os.environ["QT_API"] = "pyside6"
    from PySide6.QtCore import QTimer
    from PySide6.QtWidgets import QApplication
    from app import launch
    from app.__main__ import window_parser

    DRAIN = 400_000  # slider moves: more references than None holds without a reserve

    def soak():
        window = next(w for w in QApplication.topLevelWidgets()
                      if type(w).__name__ == "MainWindow")
        if window.model.dataset is None:
            QTimer.singleShot(100, soak)
            return
        count = len(window.model.spectrum)
        for i in range(60):  # slider steps through the model: shapes, panels, renders
            window.model.set_index(i * 7919 % count)
            QApplication.processEvents()
        print("None references before the drain:", sys.getrefcount(None), flush=True)
        slider = window.alpha_panel.slider
        slider.blockSignals(True)  # the calls alone, not a step of the window each
        for i in range(DRAIN):
            slider.setValue(i % 100)
        slider.blockSignals(False)
        window.close()

    app = QApplication(sys.argv[:1])  # the one run_window uses: the timer needs it
    QTimer.singleShot(100, soak)
    args = window_parser().parse_args([sys.argv[1], "--size", "640x480"])
    code = launch.run_window(args)
    print("run_window returned", code, flush=True)
    sys.exit(code)
""")


@pytest.mark.skipif(sys.version_info >= (3, 12), reason="None is immortal from CPython 3.12")
def test_the_window_exits_cleanly_after_a_long_session(tmp_path, qapp_cls):
    env = {**os.environ, "PYTHONPATH": str(Path(__file__).parents[1]), "QT_API": "pyside6",
           "ALPHASCOOP_CACHE_DIR": str(tmp_path / "cache"), "HOME": str(tmp_path)}
    run = subprocess.run([sys.executable, "-c", SCRIPT, str(SAMPLE_PATH)], env=env,
                         capture_output=True, text=True, timeout=300)
    assert "Fatal Python error" not in run.stderr, run.stderr[-2000:]
    assert run.returncode == 0, run.stderr[-2000:]
    assert "run_window returned 0" in run.stdout


def test_the_reserve_is_given_once():
    from app.none_guard import RESERVE, keep_none_alive, needed

    keep_none_alive()
    after = sys.getrefcount(None)
    keep_none_alive()
    assert sys.getrefcount(None) - after < 1000  # no second reserve
    assert not needed() or after >= RESERVE

"""Test session set-up: Qt binding, a private Xvfb display for GUI tests, plotter leak checks,
and in CI no skip but the shared data's (tests/skip_guard.py)."""

from __future__ import annotations

import os

os.environ["QT_API"] = "pyside6"
os.environ.pop("ALPHASCOOP_BACKEND", None)  # the window's automatic backend choice is tested

import shutil
import subprocess
import sys
import tempfile
from collections.abc import Iterator

import numpy as np
import pytest
from hypothesis import settings
from reference import data_dir
from skip_guard import SkipGuard, in_ci, xdist_role

# Property tests draw the same examples on every run (the CI must not depend on luck);
# HYPOTHESIS_PROFILE=explore draws new ones, to look for failures on purpose.
settings.register_profile("fixed", derandomize=True, database=None)
settings.register_profile("explore")
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "fixed"))

XVFB_ARGS = ("-screen", "0", "1280x1024x24", "-nolisten", "tcp")
XVFB_STOP_TIMEOUT_S = 20.0
XVFB_KEY = pytest.StashKey[subprocess.Popen]()
XVFB_ERROR_KEY = pytest.StashKey[str]()
CACHE_KEY = pytest.StashKey[str]()
NO_XVFB = (
    "GUI tests need an X display, and Xvfb is not installed: run ./.ci/setup "
    "(or apt-get install xvfb libxcb-icccm4 libxcb-keysyms1), or set DISPLAY."
)


def start_xvfb(xvfb: str) -> subprocess.Popen:
    """Start Xvfb on a free display (it reports which through -displayfd); set DISPLAY."""
    read_fd, write_fd = os.pipe()
    process = subprocess.Popen(
        [xvfb, "-displayfd", str(write_fd), *XVFB_ARGS],
        pass_fds=(write_fd,), stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
    )
    os.close(write_fd)
    with os.fdopen(read_fd) as stream:
        number = stream.readline().strip()
    if not number.isdigit():
        process.kill()
        raise RuntimeError(f"Xvfb did not start (exit status {process.wait()})")
    os.environ["DISPLAY"] = f":{number}"
    return process


def pytest_configure(config: pytest.Config) -> None:
    """The skip guard watches every test of the run (benchmarks/ too); it fails a CI run
    that skipped a test for any reason but the shared data's absence."""
    config.pluginmanager.register(SkipGuard(data_dir() is not None, in_ci(), xdist_role(config)),
                                  "alphascoop-skip-guard")


MAX_WORKERS = 4  # real-scan tests hold 2-3 GB each; more workers add memory, not speed


def pytest_xdist_auto_num_workers(config: pytest.Config) -> int:
    """`-n auto` (the default, pyproject addopts): one worker per core, at most MAX_WORKERS."""
    return max(1, min(MAX_WORKERS, os.cpu_count() or 1))


def pytest_sessionstart(session: pytest.Session) -> None:
    """Private table cache for the session; a display of its own when the machine has none."""
    cache = tempfile.mkdtemp(prefix="alphascoop-test-cache-")
    session.config.stash[CACHE_KEY] = cache
    os.environ["ALPHASCOOP_CACHE_DIR"] = cache
    if os.environ.get("DISPLAY") or os.environ.get("WAYLAND_DISPLAY"):
        return
    xvfb = shutil.which("Xvfb")
    if xvfb is None:
        session.config.stash[XVFB_ERROR_KEY] = NO_XVFB
        return
    session.config.stash[XVFB_KEY] = start_xvfb(xvfb)


def pytest_sessionfinish(session: pytest.Session) -> None:
    """Remove the session's cache; stop the Xvfb this session started, if any."""
    cache = session.config.stash.get(CACHE_KEY, None)
    if cache:
        shutil.rmtree(cache, ignore_errors=True)
    process = session.config.stash.get(XVFB_KEY, None)
    if process is None:
        return
    process.terminate()
    try:
        process.wait(timeout=XVFB_STOP_TIMEOUT_S)
    except subprocess.TimeoutExpired:
        process.kill()


@pytest.fixture(scope="session")
def qapp_cls(request: pytest.FixtureRequest) -> type:
    """pytest-qt's QApplication class; fails GUI tests plainly when there is no display."""
    error = request.config.stash.get(XVFB_ERROR_KEY, None)
    if error:
        pytest.fail(error)
    from PySide6.QtWidgets import QApplication

    return QApplication


def open_plotters() -> set[str]:
    """Names of the pyvista plotters alive now (none if pyvista was never imported)."""
    if "pyvista" not in sys.modules:
        return set()
    from pyvista.plotting import _ALL_PLOTTERS

    return set(_ALL_PLOTTERS)


@pytest.fixture(autouse=True)
def no_leaked_plotters() -> Iterator[None]:
    """Fail a test that leaves a pyvista plotter open (close them in teardown)."""
    before = open_plotters()
    yield
    leaked = open_plotters() - before
    if leaked:
        from pyvista.plotting import _ALL_PLOTTERS

        for name in leaked:
            _ALL_PLOTTERS[name].close()
        pytest.fail(f"test left {len(leaked)} pyvista plotter(s) open")


def image_contrast(image: np.ndarray) -> float:
    """Standard deviation of an (h, w, c) uint8 screenshot: ~0 for a blank or black frame."""
    return float(np.asarray(image, dtype=np.float64).std())


BUILD_TIMEOUT_MS = 120_000


@pytest.fixture
def window(qtbot, tmp_path):
    """A shown MainWindow with private settings, closed (with its plotter) in teardown."""
    from PySide6.QtCore import QSettings

    from app.main_window import MainWindow

    win = MainWindow(QSettings(str(tmp_path / "settings.ini"), QSettings.Format.IniFormat))
    qtbot.addWidget(win)
    win.resize(900, 650)
    win.show()
    qtbot.waitExposed(win)
    yield win
    win.close()


def open_and_wait(qtbot, win, path) -> None:
    """Open path the way a user does (window.open_path) and wait until it is shown with its
    topology and a molecule's measures (the slider works before: see
    test_app_topology_later, test_app_measures_later)."""
    with qtbot.waitSignal(win.model.datasetChanged, timeout=BUILD_TIMEOUT_MS):
        win.open_path(path)
    wait_for_topology(qtbot, win)
    qtbot.waitUntil(lambda: not win.model.dataset.needs_measures, timeout=BUILD_TIMEOUT_MS)


def wait_for_topology(qtbot, win) -> None:
    """Wait until the shown dataset's topology (signatures, optimal alpha) has arrived."""
    qtbot.waitUntil(lambda: win.model.dataset.has_topology, timeout=BUILD_TIMEOUT_MS)


def fake_export_dialog(target, *, manifold: bool | None = None, seen: list | None = None):
    """A stand-in for app.export_dialog.run_dialog: chooses `target` (and the manifold box,
    if given) as a user would, records the dialog's default file name and box in `seen`."""
    def run(dialog) -> bool:
        if seen is not None:
            seen.append((dialog.selectedFiles()[0], dialog.manifold.isChecked()))
        if manifold is not None:
            dialog.manifold.setChecked(manifold)
        dialog.selectFile(str(target))
        return True
    return run

"""In CI a skip fails the run, but the shared data's absence while it is absent (skip_guard):
checked on small runs of pytest in a folder of their own."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest
from reference import COMPARE_EXTRA, DATA_ABSENT
from skip_guard import accepted, in_ci

TESTS = Path(__file__).resolve().parent

SKIPS = f'''
import pytest

def test_runs():
    assert True

@pytest.mark.skipif(True, reason={DATA_ABSENT!r})
def test_needs_the_shared_data():
    pass
'''
OTHER_SKIP = '''
import pytest

def test_needs_a_library():
    pytest.importorskip("no_such_library_anywhere")
'''
MODULE_SKIP = '''
import pytest

pytest.importorskip("no_such_library_anywhere")

def test_never_collected():
    pass
'''


XFAILS = '''
import pytest

@pytest.mark.xfail(strict=True, reason="a known gap, asserted still there")
def test_known_gap():
    assert False

@pytest.mark.xfail(reason="hides whatever happens")
def test_hidden():
    assert False
'''


def run(folder: Path, files: dict[str, str], *, data_present: bool, ci: str | None,
        workers: int = 0) -> subprocess.CompletedProcess:
    """pytest on `files` in folder, with the guard told whether the shared data is there;
    workers > 0 runs them on that many pytest-xdist workers."""
    folder.mkdir()
    (folder / "conftest.py").write_text(
        f"import sys\nsys.path.insert(0, {str(TESTS)!r})\n"
        "from skip_guard import SkipGuard, in_ci, xdist_role\n\n"
        "def pytest_configure(config):\n"
        f"    config.pluginmanager.register(SkipGuard({data_present}, in_ci(), "
        "xdist_role(config)), 'guard')\n")
    for name, text in files.items():
        (folder / name).write_text(text)
    env = {key: value for key, value in os.environ.items() if key != "CI"}
    if ci is not None:
        env["CI"] = ci
    return subprocess.run([sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider",
                           "-n", str(workers), str(folder)], cwd=folder, env=env,
                          capture_output=True, text=True, timeout=120)


def test_in_ci_only_the_absent_data_skips(tmp_path):
    done = run(tmp_path / "a", {"test_a.py": SKIPS}, data_present=False, ci="true")
    assert done.returncode == 0, done.stdout
    assert "1 passed, 1 skipped" in done.stdout and "refused" not in done.stdout


def test_in_ci_a_missing_library_fails_the_run(tmp_path):
    done = run(tmp_path / "b", {"test_a.py": SKIPS, "test_b.py": OTHER_SKIP,
                                "test_c.py": MODULE_SKIP}, data_present=False, ci="true")
    assert done.returncode == 1, done.stdout
    assert "skips refused in CI" in done.stdout
    assert "test_b.py::test_needs_a_library: could not import" in done.stdout
    assert "test_c.py: could not import" in done.stdout
    assert "test_needs_the_shared_data" not in done.stdout.split("skips refused in CI")[1]


def test_in_ci_with_the_data_there_no_skip_passes(tmp_path):
    done = run(tmp_path / "c", {"test_a.py": SKIPS}, data_present=True, ci="true")
    assert done.returncode == 1, done.stdout
    assert "test_a.py::test_needs_the_shared_data: shared real-scan" in done.stdout


def test_on_xdist_workers_the_controller_fails_the_run_for_their_skips(tmp_path):
    done = run(tmp_path / "x", {"test_a.py": SKIPS, "test_b.py": OTHER_SKIP,
                                "test_c.py": MODULE_SKIP, "test_d.py": XFAILS},
               data_present=False, ci="true", workers=2)
    assert done.returncode == 1, done.stdout
    refused = done.stdout.split("skips refused in CI")[1]
    assert "test_b.py::test_needs_a_library: could not import" in refused
    assert refused.count("test_c.py: could not import") == 1
    assert "test_d.py::test_hidden: xfail" in refused
    assert "test_known_gap" not in refused and "test_needs_the_shared_data" not in refused


def test_on_xdist_workers_accepted_skips_pass(tmp_path):
    done = run(tmp_path / "y", {"test_a.py": SKIPS}, data_present=False, ci="true", workers=2)
    assert done.returncode == 0, done.stdout
    assert "refused" not in done.stdout


def test_outside_ci_skips_are_reported_not_failed(tmp_path):
    done = run(tmp_path / "d", {"test_b.py": OTHER_SKIP}, data_present=False, ci=None)
    assert done.returncode == 0, done.stdout
    assert "refused" not in done.stdout


@pytest.mark.parametrize(("value", "expected"), [("true", True), ("1", True), ("TRUE", True),
                                                 ("", False), ("false", False), ("0", False)])
def test_ci_variable(value, expected):
    assert in_ci({"CI": value}) is expected


def test_only_the_data_reason_is_accepted_and_only_without_the_data():
    assert accepted(DATA_ABSENT, data_present=False)
    assert not accepted(DATA_ABSENT, data_present=True)
    assert not accepted("could not import 'gudhi': No module named 'gudhi'", data_present=False)
    assert accepted(COMPARE_EXTRA, data_present=True)

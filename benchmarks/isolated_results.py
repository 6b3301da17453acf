"""The harness's tests write their benchmark results to a temporary folder, never to
benchmarks/results/ (whose JSON holds the figures of real runs). Each benchmarks/test_*.py
imports the fixture (a conftest.py here would shadow tests/conftest.py: both import as
`conftest`)."""

from __future__ import annotations

import pytest
from results import FOLDER_ENV


@pytest.fixture(autouse=True)
def results_elsewhere(tmp_path, monkeypatch):
    """Point benchmarks/results.py (and any child process) at a folder of this test's own."""
    monkeypatch.setenv(FOLDER_ENV, str(tmp_path / "results"))

"""The repository's top level is decided by the project brief: nothing else lands there."""

from __future__ import annotations

import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
# Decided in the brief: exactly these (plus dotfiles such as .ci/ and .gitignore);
# benchmarks/ is the benchmark folder README.md names, ARCHITECTURE.md the one document
# beside the README. Pictures go under assets/.
ALLOWED = {"pyproject.toml", "app", "core", "tests", "assets", "README.md", "ARCHITECTURE.md",
           "benchmarks"}


def _tracked_top_level() -> set[str]:
    if not (ROOT / ".git").exists():  # an unpacked archive: nothing is tracked
        pytest.skip("not a git checkout")
    out = subprocess.run(["git", "ls-files"], cwd=ROOT, capture_output=True, text=True,
                         check=True).stdout  # a checkout where git fails: the test fails
    return {line.split("/", 1)[0] for line in out.splitlines() if line}


def test_top_level_is_exactly_the_decided_layout() -> None:
    extra = {name for name in _tracked_top_level() - ALLOWED if not name.startswith(".")}
    assert not extra, f"top-level entries not in the decided layout: {sorted(extra)}"


def test_assets_folder_is_at_the_top_level() -> None:
    assert (ROOT / "assets").is_dir(), "assets/ (bundled sample data and icons) must stay"
    assert "benchmarks" in (ROOT / "README.md").read_text(encoding="utf-8")

"""README.md's examples run and print what it says: its Python blocks execute, its console
transcript prints the lines shown (build times aside), its molecule output is the real one."""

from __future__ import annotations

import os
import re
import subprocess
import sys
from pathlib import Path

import pytest
from reference import DATA_ABSENT, data_dir

ROOT = Path(__file__).resolve().parents[1]
README = ROOT / "README.md"
FENCE = re.compile(r"^```(\w+)\n(.*?)^```$", re.S | re.M)
TIMING = re.compile(r"\((built|rebuilt) in [0-9.]+ s")


def blocks(language: str) -> list[str]:
    """The README's fenced blocks of one language, in order."""
    return [body for lang, body in FENCE.findall(README.read_text()) if lang == language]


@pytest.fixture
def workdir(tmp_path, monkeypatch) -> Path:
    """A folder laid out like the repository for the examples (assets/sample.ply and, when the
    shared data is there, 1A8O.pdb), with a table cache of its own."""
    (tmp_path / "assets").mkdir()
    (tmp_path / "assets" / "sample.ply").symlink_to(ROOT / "assets" / "sample.ply")
    shared = data_dir()
    if shared is not None and (shared / "1A8O.pdb").is_file():
        (tmp_path / "1A8O.pdb").symlink_to(shared / "1A8O.pdb")
    monkeypatch.chdir(tmp_path)
    monkeypatch.setenv("ALPHASCOOP_CACHE_DIR", str(tmp_path / "cache"))
    return tmp_path


def run_cli(args: list[str], cwd: Path) -> str:
    """`alphascoop ARGS` as the README runs it (python -m app), its standard output."""
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    done = subprocess.run([sys.executable, "-m", "app", *args], cwd=cwd, env=env,
                          capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    return done.stdout


def test_the_readme_has_the_examples_this_file_runs() -> None:
    assert len(blocks("python")) == 3 and len(blocks("console")) == 1
    assert README.read_text().startswith("# Alpha Scoop\n\n```bash\n./.ci/setup && "
                                         ".venv/bin/alphascoop ")


@pytest.mark.parametrize("number", range(3))
def test_python_example_runs(number: int, workdir: Path) -> None:
    code = blocks("python")[number]
    if "1A8O.pdb" in code and not (workdir / "1A8O.pdb").exists():
        pytest.skip(DATA_ABSENT)
    done = subprocess.run([sys.executable, "-c", code], cwd=workdir, capture_output=True,
                          text=True, timeout=300, env=dict(os.environ, PYTHONPATH=str(ROOT)))
    assert done.returncode == 0, done.stderr
    for comment in re.findall(r"print\(.*\)\s+# (.+)", code):  # the printed values it states
        for value in re.findall(r"[0-9][0-9.]*", comment):
            assert value.rstrip(".") in done.stdout, (comment, done.stdout)


def test_console_transcript_prints_what_the_readme_shows(workdir: Path) -> None:
    transcript = blocks("console")[0]
    commands = re.findall(r"^\$ alphascoop (.+)$", transcript, re.M)
    shown = re.split(r"^\$ alphascoop .+\n", transcript, flags=re.M)[1:]
    assert len(commands) == len(shown) == 2
    for command, expected in zip(commands, shown, strict=True):
        printed = run_cli(command.split(), workdir)
        assert TIMING.sub(r"(\1 in X s", printed) == TIMING.sub(r"(\1 in X s", expected)


def test_molecule_output_is_the_real_one(workdir: Path) -> None:
    if not (workdir / "1A8O.pdb").exists():
        pytest.skip(DATA_ABSENT)
    shown = next(body for body in blocks("text") if body.startswith("atoms "))
    printed = run_cli(["info", "1A8O.pdb"], workdir)
    assert printed.endswith(shown)


@pytest.mark.parametrize("name", ["README.md", "ARCHITECTURE.md"])
def test_every_path_the_docs_cite_exists(name: str) -> None:
    text = (ROOT / name).read_text()
    cited = set(re.findall(r"`((?:core|app|tests|benchmarks|assets|\.ci)/[\w./*-]*)`", text))
    assert len(cited) > 5
    missing = sorted(path for path in cited if not any(ROOT.glob(path.rstrip("/"))))
    assert not missing, missing


def test_every_core_module_the_architecture_names_exists() -> None:
    rows = re.findall(r"^\| `(\w+)/` \| ([^|]+) \|", (ROOT / "ARCHITECTURE.md").read_text(),
                      re.M)
    assert len(rows) >= 7
    for family, modules in rows:
        for module in re.findall(r"`(\w+)`", modules):
            assert (ROOT / "core" / family / f"{module}.py").is_file(), (family, module)

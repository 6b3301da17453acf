"""report.py: the READMEs' generated figures are the results' (benchmarks/results/*.json), and
a figure edited by hand, or a result the READMEs do not show, is caught."""

from __future__ import annotations

import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
import report
from isolated_results import results_elsewhere  # noqa: F401 (autouse fixture)
from results import RESULTS, Figure, save


def test_both_readmes_are_the_reports_output() -> None:
    assert report.stale(RESULTS) == [], "run python benchmarks/report.py --write"


def test_check_exits_zero_on_the_repository() -> None:
    done = subprocess.run([sys.executable, str(Path(report.__file__)), "--check"],
                          capture_output=True, text=True, timeout=60)
    assert done.returncode == 0, done.stderr


@pytest.fixture
def copies(tmp_path: Path) -> tuple[Path, Path]:
    """Copies of both READMEs, as the report would write them from the committed results."""
    bench, readme = tmp_path / "bench.md", tmp_path / "readme.md"
    shutil.copy(report.BENCH_README, bench)
    shutil.copy(report.USER_README, readme)
    return bench, readme


def _edit_first_number(path: Path, begin: str, end: str) -> None:
    """Change one digit of the first figure between the markers, as a hand edit would."""
    text = path.read_text()
    start, stop = text.index(begin), text.index(end, text.index(begin))
    block = text[start:stop]
    row = next(line for line in block.splitlines() if re.search(r"\| [0-9]", line))
    edited = re.sub(r"(\| )([0-9])", lambda m: m.group(1) + str((int(m.group(2)) + 1) % 10),
                    row, count=1)
    path.write_text(text[:start] + block.replace(row, edited) + text[stop:])


def test_a_hand_edited_figure_in_readme_fails_the_check(copies) -> None:
    bench, readme = copies
    if "| " not in readme.read_text().split("<!-- figures:begin -->")[1].split("\n", 3)[-1]:
        pytest.skip("no result behind README.md's figures yet")
    _edit_first_number(readme, "<!-- figures:begin -->", "<!-- figures:end -->")
    assert report.stale(RESULTS, bench, readme) == [readme]


def test_a_hand_edited_figure_in_the_benchmarks_readme_fails_the_check(copies) -> None:
    bench, readme = copies
    found = report.results(RESULTS)
    if not found:
        pytest.skip("no results committed yet")
    name = sorted(found)[0]
    _edit_first_number(bench, f"<!-- report:begin {name} -->", f"<!-- report:end {name} -->")
    assert report.stale(RESULTS, bench, readme) == [bench]


def test_blocks_are_made_from_the_results(tmp_path: Path) -> None:
    folder = tmp_path / "results"
    save("bench_toy", [Figure("step", "toy step, 10 points", 0.002, "s", "toy build", 4.0,
                              "<= 0.001"),
                       Figure("area", "toy area", 12.5, "Å²")], notes=["A toy."],
         folder=folder)
    found = report.results(folder)
    bench = "# B\n\n<!-- report:begin bench_toy -->\nold\n<!-- report:end bench_toy -->\n"
    made = report.render_benchmarks(bench, found)
    assert "| toy step, 10 points | 0.002 s | toy build: 4 s | 0.0005x | <= 0.001: met |" in made
    assert "| toy area | 12.5 Å² | - | - | - |" in made and "A toy." in made
    assert "old" not in made and f"{found['bench_toy']['machine']['cpu_count']} CPUs" in made
    assert report.render_benchmarks(made, found) == made  # writing twice changes nothing


def test_a_result_without_a_section_gets_one(tmp_path: Path) -> None:
    folder = tmp_path / "results"
    save("bench_new", [Figure("x", "x, 5 points", 1.0, "s", "y", 2.0)], folder=folder)
    made = report.render_benchmarks("# B\n", report.results(folder))
    assert "## bench_new\n\n<!-- report:begin bench_new -->" in made
    assert "| x, 5 points | 1 s | y: 2 s | 0.5x | - |" in made


def test_readme_figures_give_the_cpu_ratio_beside_the_wall_one(tmp_path: Path) -> None:
    folder = tmp_path / "results"
    save("bench_modes", [Figure("density_wall", "density build, wall, 9 points", 3.0, "s",
                                "classic build", 2.0, "<= 1.3"),
                         Figure("density_cpu", "density build, CPU, 9 points", 1.0, "s",
                                "classic build", 4.0, "<= 1.3")], folder=folder)
    made = report.figures_block(report.results(folder))
    assert "| density build, 9 points | 3 s | classic build: 2 s | 1.5x | 0.25x |" in made


def test_readme_figures_only_show_featured_results(tmp_path: Path) -> None:
    folder = tmp_path / "results"
    save("bench_slider", [Figure("drag_step_max_wall", "slider step, drag", 0.05, "s",
                                 "table build", 60.0, "<= 0.001")], folder=folder)
    text = "x\n<!-- figures:begin -->\n<!-- figures:end -->\n"
    made = report.render_readme(text, report.results(folder))
    rows = [line for line in made.splitlines() if line.startswith("| slider")]
    cpus = report.results(folder)["bench_slider"]["machine"]["cpu_count"]
    assert rows == ["| slider step, drag | 0.05 s | table build: 60 s | 0.000833x | - | "
                    f"`bench_slider`, {cpus} CPUs |"]
    with pytest.raises(ValueError, match="figures:begin"):
        report.render_readme("no markers", {})


def test_a_result_names_the_commit_its_run_started_on(monkeypatch) -> None:
    import results

    head, dirty_now = results._commit()
    monkeypatch.setattr(results, "_STARTED", (head, False))
    assert results._run_commit() == (head, dirty_now)
    monkeypatch.setattr(results, "_STARTED", (head, True))
    assert results._run_commit() == (head, True)
    first = results._git("rev-list", "--max-parents=0", "HEAD").splitlines()[0]
    monkeypatch.setattr(results, "_STARTED", (first, False))
    assert results._run_commit() == (first, True)  # the code changed since the run started

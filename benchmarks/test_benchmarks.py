"""Tests of the benchmark harness: dataset, isolation, memory probe, ratios (pytest benchmarks/)."""

from __future__ import annotations

import json

import numpy as np
import pytest
from bench_core import main
from core_report import figures, format_tables, ratios
from datasets import TORUS_R, TORUS_TUBE, noisy_torus
from isolate import Probe, run_isolated
from isolated_results import results_elsewhere  # noqa: F401 (autouse fixture)

from tests.reference import DATA_ABSENT


def _allocate(mib: int) -> dict:
    """Child task: touch mib MiB of memory and report the probe's figures."""
    probe = Probe()
    block = np.ones(mib * 1024 * 1024 // 8)
    return probe.result(total=float(block.sum()))


def _fail() -> dict:
    """Child task that raises, as a missing library would."""
    raise ImportError("no such library")


def test_torus_is_deterministic_per_seed():
    assert np.array_equal(noisy_torus(500, seed=3), noisy_torus(500, seed=3))
    assert not np.array_equal(noisy_torus(500, seed=3), noisy_torus(500, seed=4))


def test_torus_points_lie_in_a_thin_shell_around_the_surface():
    points = noisy_torus(20_000, seed=1)
    ring = np.hypot(points[:, 0], points[:, 1]) - TORUS_R
    tube = np.hypot(ring, points[:, 2])
    assert points.shape == (20_000, 3) and points.dtype == np.float64
    assert np.abs(tube - TORUS_TUBE).max() < 6 * 0.003 * TORUS_TUBE
    assert np.std(tube) > 0.5 * 0.003 * TORUS_TUBE


def test_torus_sample_is_area_uniform():
    points = noisy_torus(40_000, seed=2)
    outer = np.hypot(points[:, 0], points[:, 1]) > TORUS_R
    expected = 0.5 + TORUS_TUBE / (np.pi * TORUS_R)
    assert abs(outer.mean() - expected) < 0.015


def test_torus_rejects_too_few_points():
    with pytest.raises(ValueError, match="at least 4"):
        noisy_torus(3)


def test_isolated_probe_sees_the_child_allocation():
    result = run_isolated(_allocate, 160)
    assert result["extra_mib"] > 140
    assert result["seconds"] > 0


def test_isolated_failure_becomes_an_error_message():
    assert run_isolated(_fail)["error"] == "ImportError: no such library"


@pytest.mark.parametrize(
    ("build", "passed"), [(1.4, True), (1.6, False), (None, None)]
)
def test_ratio_against_goal(build, passed):
    results = {"scipy": {"seconds": 1.0}}
    if build is not None:
        results["build"] = {"seconds": build}
    row = ratios(figures(results))[0]
    assert row["figure"].startswith("build / scipy") and row["passed"] is passed


def test_open3d_is_compared_at_the_same_alpha_on_both_clocks():
    flat = figures({
        "query": {"shapes": [{"alpha": 0.5, "seconds": 0.1, "cpu_seconds": 0.1},
                             {"alpha": 2.0, "seconds": 0.3, "cpu_seconds": 0.2},
                             {"alpha": 9.0, "seconds": 0.9, "cpu_seconds": 0.9}]},
        "open3d": {"per_alpha": [{"alpha": 0.5, "seconds": 0.5, "cpu_seconds": 0.4},
                                 {"alpha": 2.0, "seconds": 6.0, "cpu_seconds": 5.0}]}})
    assert flat["shape.worst_seconds"] == 0.9
    row = ratios(flat)[-1]
    assert row["ratio"] == pytest.approx(0.2) and row["cpu_ratio"] == pytest.approx(0.25)
    assert row["passed"] is False and row["cpu_passed"] is False


def test_verdict_shows_the_cpu_clock_when_it_disagrees():
    flat = figures({"scipy": {"seconds": 2.0, "cpu_seconds": 1.0},
                    "build": {"seconds": 2.4, "cpu_seconds": 2.0}})
    row = ratios(flat)[0]
    assert (row["passed"], row["cpu_passed"]) == (True, False)
    table = format_tables(10, {}, [row])
    assert "| PASS (cpu: FAIL) |" in table


def test_end_to_end_small_run_writes_json(tmp_path, capsys):
    out = tmp_path / "bench.json"
    assert main(["--n", "300", "--reps", "2", "--skip-gudhi", "--skip-open3d",
                 "--json", str(out)]) == 0
    run = json.loads(out.read_text())["runs"]["300"]
    assert run["results"]["scipy"]["cells"] > 300
    assert len(run["ratios"]) == 7
    assert "| build / scipy Delaunay (time) |" in capsys.readouterr().out


@pytest.mark.parametrize("argv", [["--n", "3"], ["--reps", "0"], ["--json", "/no/such/dir/x.json"]])
def test_bad_options_exit_with_a_message(argv, capsys):
    with pytest.raises(SystemExit) as stop:
        main(argv)
    assert stop.value.code == 2 and "error:" in capsys.readouterr().err


def test_slider_benchmark_end_to_end(tmp_path):
    """bench_slider.py runs on a small torus and reports every step kind against the build.
    It runs in its own process: importing it would pick VTK's window class for this one."""
    import os
    import subprocess
    import sys
    from pathlib import Path

    out = tmp_path / "slider.json"
    script = Path(__file__).with_name("bench_slider.py")
    done = subprocess.run([sys.executable, str(script), "--n", "3000", "--steps", "4",
                           "--skip-open3d", "--size", "320x240", "--json", str(out)],
                          capture_output=True, text=True, timeout=300, env=dict(os.environ))
    assert done.returncode == 0, done.stderr
    figures = json.loads(out.read_text())
    assert figures["n_points"] == 3000 and figures["build_s"] > 0
    for kind in ("arrow_step", "drag_step", "page_step"):
        assert 0 < figures[kind]["median_s"] <= figures[kind]["max_s"]
        assert f"{kind:10s} median" in done.stdout


def test_bench_modes_end_to_end(tmp_path, capsys):
    from bench_modes import main as modes_main

    out = tmp_path / "modes.json"
    assert modes_main(["--n", "2000", "--json", str(out)]) == 0
    result = json.loads(out.read_text())
    assert set(result["ratios"]) == {"density k=8", "anisotropic tau=0.5"}
    assert all(r["wall"] > 0 and r["cpu"] > 0 for r in result["ratios"].values())
    assert "neighbours" in result["builds"]["density k=8"]["stages"]
    assert len(result["load"]) == 2
    out = capsys.readouterr().out
    assert "ratio" in out and "load average" in out


def test_weighted_packing_radii_span_one_to_two_spacings() -> None:
    from scipy.spatial import cKDTree

    from benchmarks.bench_weighted import packing

    points, weights = packing(2000, seed=3)
    dist, _ = cKDTree(points).query(points, k=2)
    spacing = np.median(dist[:, 1])
    radii = np.sqrt(weights)
    assert points.shape == (2000, 3) and weights.shape == (2000,)
    assert radii.min() >= 0.9 * spacing and radii.max() <= 2.1 * spacing
    assert radii.max() / radii.min() > 1.8


def test_molecule_benchmark_small_run(tmp_path) -> None:
    from benchmarks.bench_molecule import SOURCE, write_copies
    from benchmarks.bench_molecule import main as bench_main

    if not SOURCE.is_file():
        pytest.skip(DATA_ABSENT)
    assert write_copies(2, tmp_path / "two.pdb") == 1112
    from core.io.molecule import read_molecule

    assert write_copies(70, tmp_path / "many.pdb") == 70 * 556  # chain letters reused
    assert len(read_molecule(tmp_path / "many.pdb").centres) == 70 * 556  # no atom merged
    assert bench_main(["--sizes", "2", "--results", str(tmp_path)]) == 0
    result = json.loads((tmp_path / "molecule.json").read_text())
    names = {f["name"]: f for f in result["figures"]}
    assert {"end_to_end_1112", "everything_1112", "weighted_build_1112",
            "end_to_end_1112_cpu", "weighted_build_1112_cpu"} <= set(names)
    assert all(f["anchor_value"] > 0 and f["ratio"] > 0 for f in names.values())
    row = result["tables"][0]["rows"][0]
    assert row[0] == 1112 and row[6] > 0 and row[7] > 0  # our and freesasa's areas


def test_bench_passes_compares_two_checkouts_stage_by_stage(tmp_path, capsys) -> None:
    import os

    import bench_passes

    root = os.path.dirname(os.path.dirname(os.path.abspath(bench_passes.__file__)))
    out = tmp_path / "passes.json"
    assert bench_passes.main(["--before", root, "--n", "300", "--rounds", "1",
                              "--json", str(out)]) == 0
    printed = capsys.readouterr().out
    for stage in ("circumspheres of cells", "facets", "edges", "topology", "signatures",
                  "table passes (sum)", "topology pass (sum)"):
        assert f"| {stage} |" in printed
    runs = json.loads(out.read_text())["300"]
    assert len(runs["before"]) == len(runs["after"]) == 1
    assert runs["after"][0]["peak MiB"] > 0 and runs["gudhi"] is None
    with pytest.raises(SystemExit):
        bench_passes.main(["--before", str(tmp_path)])  # no core/ there


def test_bench_cache_reopens_both_layouts_from_the_cache(tmp_path, capsys) -> None:
    import os

    import bench_cache

    root = os.path.dirname(os.path.dirname(os.path.abspath(bench_cache.__file__)))
    out = tmp_path / "cache.json"
    assert bench_cache.main(["--n", "2000", "--reps", "1", "--reference-tree", root,
                             "--json", str(out)]) == 0
    assert "cached reopen, 2,000 points, wall" in capsys.readouterr().out
    run = json.loads(out.read_text())["results"]["2000"]
    assert run["compact"]["seconds"] > 0 and run["reference"]["seconds"] > 0
    assert run["compact_bytes"] < run["full_bytes"]
    assert {"enter_values", "sig_betti_steps"} <= set(run["members"])
    with pytest.raises(SystemExit):
        bench_cache.main(["--reference-tree", str(tmp_path)])  # no core/ there


def test_first_open_ratios_on_both_clocks_and_memory():
    """bench_first_open: time goals on wall and CPU clocks, the peak of either window process
    against scipy's, and the soak's worst re-open against the first open."""
    from bench_first_open import format_report, ratio_rows

    results = {
        "scipy Delaunay": {"seconds": 40.0, "cpu_seconds": 40.0, "peak_mib": 2000.0},
        "gudhi fast": {"seconds": 80.0, "cpu_seconds": 80.0, "peak_mib": 2700.0},
        "window: slider live": {"seconds": 40.0, "cpu_seconds": 60.0},
        "window: first frame": {"seconds": 50.0, "cpu_seconds": 62.0},
        "window": {"peak_mib": 3000.0, "child_peak_mib": 4000.0, "rss_after_mib": 2000.0,
                   "child_peaks_mib": {"alphascoop-build": 4000.0, "alphascoop-half": 1400.0,
                                       "alphascoop-topology": 3500.0},
                   "soak": {"after_open_mib": [2100.0, 2500.0], "after_cancel_mib": [500.0],
                            "open_seconds": [9.0, 7.0], "build_processes_left": 0,
                            "old_datasets_alive": 0, "peak_mib": 6000.0}},
    }
    rows = {name: (ratio, met) for name, _, _, ratio, _, met in ratio_rows(results)}
    assert rows["window: slider live / gudhi fast (time)"] == (0.5, True)
    assert rows["window: slider live / gudhi fast (CPU)"] == (0.75, False)
    assert rows["window: first frame / gudhi fast (time)"] == (0.625, False)
    # the build and its gmsh half run at once: their peaks are summed (4000 + 1400)
    assert rows["window first open peak / scipy peak (MiB)"] == (2.7, False)
    assert rows["soak: worst RSS after a re-open / after the first open (MiB)"] == (1.25, False)
    assert rows["soak: worst RSS after a re-open of the torus / after its first (MiB)"] == (
        1.25, False)
    assert "soak: worst RSS after a re-open of the cube / after its first (MiB)" not in rows
    assert "soak: worst RSS after a re-open of the bunny / after its first (MiB)" in {
        row[0] for row in ratio_rows(results, "bunny")}
    assert not any(name.startswith("core build") for name in rows)  # not measured: no row
    assert "| window: slider live / gudhi fast (time) | 40 | 80 | 0.5 | <= 0.6 | yes |" in (
        format_report(1000, results))
    assert not any(name.startswith("window, qhull") for name in rows)
    results["window, qhull: slider live"] = {"seconds": 56.0, "cpu_seconds": 70.0}
    qhull = {name: (ratio, goal, met) for name, _, _, ratio, goal, met in ratio_rows(results)}
    assert qhull["window, qhull: slider live / gudhi fast (time)"] == (0.7, None, None)
    report = format_report(1000, results, "bunny")
    assert report.startswith("### n = 1,000, bunny")
    assert "| window, qhull: slider live / gudhi fast (time) | 56 | 80 | 0.7 |  | reported |" in (
        report)


def test_first_open_steps_and_soak_cycles_are_chosen_on_the_command_line():
    """bench_first_open --steps runs those steps in the order given; --soak-cycles N bounds
    the soak (and implies it); a wrong step is a one-line usage error."""
    from bench_first_open import parse_args

    args = parse_args(["--n", "1000", "--steps", "window,gudhi,window", "--soak-cycles", "2"])
    assert args.steps == ["window", "gudhi"] and args.cycles == 2
    assert parse_args(["--soak"]).cycles == 10 and parse_args([]).cycles == 0
    assert parse_args(["--skip-gudhi"]).steps == ["scipy", "qhull", "gmsh", "window"]
    assert parse_args(["--steps", "window-qhull,gudhi"]).steps == ["window-qhull", "gudhi"]
    assert parse_args([]).set == "torus" and parse_args(["--set", "bunny"]).set == "bunny"
    for wrong in (["--steps", "window,cgal"], ["--steps", ","], ["--soak-cycles", "0"],
                  ["--set", "dragon"]):
        with pytest.raises(SystemExit):
            parse_args(wrong)


def test_bunny_scan_lies_near_the_bunny_and_is_deterministic() -> None:
    from benchmarks.datasets import bunny_scan, shared_data

    folder = shared_data()
    if not (folder / "bunny.ply").is_file():
        pytest.skip(DATA_ABSENT)
    points = bunny_scan(3000, seed=2, mesh=str(folder / "bunny.ply"))
    assert points.shape == (3000, 3)
    assert np.array_equal(points, bunny_scan(3000, seed=2, mesh=str(folder / "bunny.ply")))
    assert np.array_equal(points, np.round(points, 6))  # 1 µm, as the ASCII PLY
    assert points.min(axis=0)[1] > 0.03 and points.max(axis=0)[1] < 0.19  # bunny's bbox


def test_backend_benchmark_small_run(tmp_path, capsys) -> None:
    from benchmarks.bench_backends import main as backends_main

    out = tmp_path / "backends.json"
    steps = "scipy Delaunay,qhull triangulation,gmsh triangulation,build qhull"
    assert backends_main(["--n", "3000", "--sets", "torus", "--steps", steps,
                          "--json", str(out)]) == 0
    result = json.loads(out.read_text())["results"]["torus"]
    delaunay = result["scipy Delaunay"]
    assert delaunay["cells"] > 0 and result["build qhull"]["backend"] == "qhull"
    assert result["qhull triangulation"]["cells"] == delaunay["cells"]
    assert "error" not in result["gmsh triangulation"] or "gmsh" in result[
        "gmsh triangulation"]["error"]
    assert "gmsh triangulation / scipy Delaunay" in capsys.readouterr().out

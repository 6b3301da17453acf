"""`alphascoop info` / `export` end to end on the shared real files (small ones)."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from reference import data_dir, needs_data

from app.cli import main

DATA = data_dir()


@pytest.fixture(autouse=True)
def cache(tmp_path, monkeypatch):
    """Every test gets its own empty table cache."""
    monkeypatch.setenv("ALPHASCOOP_CACHE_DIR", str(tmp_path / "cache"))
    return tmp_path / "cache"


def run(capsys, *argv) -> tuple[int, str, str]:
    """(exit status, stdout, stderr) of main(argv)."""
    code = main([str(a) for a in argv])
    out, err = capsys.readouterr()
    return code, out, err


@needs_data
def test_info_text_milk(capsys):
    code, out, err = run(capsys, "info", DATA / "milk.pcd")
    assert code == 0 and err == ""  # no progress bar when stderr is not a terminal
    assert "13,704 of 13,704 points read" in out and "betti" in out and "tetrahedra" in out


@needs_data
def test_info_json_airports_and_cache(capsys):
    code, out, _ = run(capsys, "info", DATA / "us_airports.csv", "--json")
    info = json.loads(out)
    assert code == 0 and info["load"]["n_points"] == 3376 and info["complex"]["dim"] == 2
    assert info["alpha"] == info["default_alpha"] <= info["optimal_alpha"] and info["area"] > 0
    assert not info["complex"]["from_cache"]
    edges = info["classes"]["edges"]
    assert sum(edges.values()) == info["complex"]["edges"]
    code, out, _ = run(capsys, "info", DATA / "us_airports.csv", "--json", "--alpha", "2")
    again = json.loads(out)
    assert again["complex"]["from_cache"] and again["alpha"] == 2.0
    assert again["area"] < info["area"]


def test_info_reports_the_source_it_saw(capsys, cache, tmp_path):
    points = tmp_path / "p.xyz"
    np.savetxt(points, np.random.default_rng(3).random((400, 3)))
    sources = []
    for _ in range(2):
        code, out, _ = run(capsys, "info", points, "--json")
        sources.append(json.loads(out)["source"])
    for entry in cache.glob("*.npz"):
        entry.write_bytes(b"damaged")
    code, out, _ = run(capsys, "info", points)
    assert sources == ["built", "cache"] and code == 0
    assert "(rebuilt in" in out and "the cached table was damaged" in out
    code, out, _ = run(capsys, "info", points, "--json", "--no-cache")
    assert json.loads(out)["source"] == "built"


@needs_data
def test_info_duplicates_and_columns(capsys):
    code, out, _ = run(capsys, "info", DATA / "plane_flat.laz", "--json", "--alpha", "0.02")
    assert code == 0 and json.loads(out)["load"]["n_duplicates"] == 9850
    code, out, _ = run(capsys, "info", DATA / "us_airports.csv", "--json", "--alpha", "1",
                       "--columns", "5,6")  # by index: plain numbers, latitude first
    assert code == 0 and json.loads(out)["load"]["bbox"][0][0] == pytest.approx(7.36722)
    assert json.loads(out)["load"]["georef"] is None


@needs_data
def test_export_manifold_ply_with_sidecar(capsys, tmp_path):
    import trimesh

    out_file = tmp_path / "milk.ply"
    code, out, _ = run(capsys, "export", DATA / "milk.pcd", "-o", out_file, "--manifold",
                       "--sidecar", "--optimal")
    assert code == 0 and out.startswith(f"wrote {out_file}")
    meta = json.loads(Path(f"{out_file}.json").read_text())
    mesh = trimesh.load(str(out_file), process=False)
    assert len(mesh.faces) == meta["n_regular_facets"] > 0
    assert "manifold_split" in meta and meta["source"].endswith("milk.pcd")


@needs_data
def test_export_geojson_area_and_optimal_k(capsys, tmp_path):
    import shapely
    from pyproj import Geod

    code, _, _ = run(capsys, "export", DATA / "us_airports.csv", "-o", tmp_path / "a.geojson",
                     "--alpha", "150000")  # metres: longitude/latitude are projected
    doc = json.loads((tmp_path / "a.geojson").read_text())
    geom = shapely.geometry.shape(doc["features"][0]["geometry"])
    area = abs(Geod(ellps="WGS84").geometry_area_perimeter(geom)[0])
    assert code == 0 and area == pytest.approx(doc["features"][0]["properties"]["area_m2"])
    code, out, _ = run(capsys, "export", DATA / "us_airports.csv", "-o", tmp_path / "a.wkt",
                       "--optimal", "20")
    assert code == 0 and "WKT" in out


@needs_data
def test_export_table_and_subsample(capsys, tmp_path):
    code, _, _ = run(capsys, "export", DATA / "plane_flat.laz", "-o", tmp_path / "t.npz",
                     "--table", "--subsample", "2000", "--no-cache")
    with np.load(tmp_path / "t.npz", allow_pickle=False) as z:
        assert code == 0 and len(z["points"]) <= 2000


BAD_CALLS = {
    "missing file": (["export", "nope.ply", "-o", "x.ply"], 1, "no such file"),
    "negative alpha": (["info", "F", "--alpha", "-1"], 2, "radius >= 0"),
    "both alphas": (["export", "F", "-o", "x.ply", "--alpha", "1", "--optimal"], 2,
                    "not allowed with"),
    "no output": (["export", "F"], 2, "required: -o"),
    "bad subsample": (["info", "F", "--subsample", "zero"], 2, "positive whole number"),
    "no command": ([], 2, "required"),
    "unknown command": (["frobnicate"], 2, "invalid choice"),
    "unknown out ext": (["export", "F", "-o", "x.abc", "--alpha", "0.01"], 1, "cannot export"),
    "3d to geojson": (["export", "F", "-o", "x.geojson", "--alpha", "0.01"], 1, "2D polygons"),
    "bad file": (["info", "BAD"], 1, "truncated PLY"),
    "missing out folder": (["export", "F", "-o", "no/x.ply", "--alpha", "0.01"], 1,
                           "does not exist"),
}


@needs_data
@pytest.mark.parametrize("case", sorted(BAD_CALLS))
def test_bad_calls_give_one_line(capsys, tmp_path, monkeypatch, case):
    argv, status, message = BAD_CALLS[case]
    bad = tmp_path / "bad.ply"
    bad.write_text("ply\nformat ascii 1.0\nelement vertex 9\nproperty float x\n"
                   "property float y\nend_header\n1 2\n")
    monkeypatch.chdir(tmp_path)
    argv = [str(DATA / "milk.pcd") if a == "F" else str(bad) if a == "BAD" else a for a in argv]
    code, out, err = run(capsys, *argv)
    assert code == status and out == ""
    assert len(err.strip().splitlines()) == 1 and message in err and "Traceback" not in err


@pytest.mark.parametrize("table", [False, True])
def test_writer_failure_is_one_line_and_keeps_old_file(capsys, tmp_path, monkeypatch, table):
    from core.export import surface
    from core.export import table as table_module

    def broken(path, *args):
        path.write_bytes(b"half")
        raise ValueError("faces must be (n, 3)\nsecond line of detail")

    writers = table_module.TABLE_WRITERS if table else surface.SURFACE_WRITERS
    monkeypatch.setitem(writers, ".npz" if table else ".ply", broken)
    np.savetxt(tmp_path / "p.xyz", np.random.default_rng(0).normal(size=(60, 3)))
    out = tmp_path / ("t.npz" if table else "s.ply")
    out.write_bytes(b"old")
    argv = ["export", tmp_path / "p.xyz", "-o", out, *(["--table"] if table else ["--alpha", 1])]
    code, stdout, err = run(capsys, *argv)
    assert code == 1 and stdout == "" and "Traceback" not in err
    assert err == f"alphascoop: error: {out}: cannot write (faces must be (n, 3))\n"
    assert out.read_bytes() == b"old" and sorted(p.name for p in tmp_path.iterdir()) == [
        "cache", "p.xyz", out.name]


def test_help_exits_zero(capsys):
    code, out, _ = run(capsys, "export", "--help")
    assert code == 0 and "--manifold" in out


@needs_data
def test_entry_point_subprocess(tmp_path):
    env = {"ALPHASCOOP_CACHE_DIR": str(tmp_path), "PATH": "/usr/bin:/bin"}
    result = subprocess.run([sys.executable, "-m", "app", "info", str(DATA / "milk.pcd"),
                             "--alpha", "0.01"], capture_output=True, text=True, timeout=300,
                            env=env, cwd=Path(__file__).resolve().parents[1])
    assert result.returncode == 0, result.stderr
    assert "volume" in result.stdout and result.stderr == ""


@needs_data
@pytest.mark.skipif(sys.platform == "win32", reason="needs a pseudo-terminal")
def test_progress_bar_on_a_terminal(tmp_path):
    import os
    import pty

    pid, fd = pty.fork()
    if pid == 0:  # child: run the CLI with stderr on the pseudo-terminal
        os.environ["ALPHASCOOP_CACHE_DIR"] = str(tmp_path)
        os.chdir(Path(__file__).resolve().parents[1])
        os.execv(sys.executable, [sys.executable, "-m", "app", "info",
                                  str(DATA / "milk.pcd"), "--alpha", "0.01"])
    chunks = []
    while True:
        try:
            chunk = os.read(fd, 65536)
        except OSError:
            break
        if not chunk:
            break
        chunks.append(chunk)
    _, status = os.waitpid(pid, 0)
    text = b"".join(chunks).decode(errors="replace")
    assert os.waitstatus_to_exitcode(status) == 0
    assert any("interval table" in s and "%|" in s for s in text.split("\r"))

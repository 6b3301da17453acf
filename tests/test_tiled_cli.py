"""`alphascoop info|export --tiled` give what the in-memory commands give at the same alpha."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
import shapely

from app.cli import main
from tests.tiled_reference import same_info

pytest.importorskip("distributed")

SHARED = Path(__file__).resolve().parents[2] / "shared" / "data"
SHARED = SHARED if SHARED.is_dir() else Path("/work/shared/data")
CORPUS = Path(__file__).parent / "data" / "corpus"
SMALL = ["--tile-points", "2000", "--memory-per-worker", "1GiB"]


def needed(path: Path) -> Path:
    if not path.exists():
        pytest.skip(f"{path} is not here")
    return path


def faces_by_coordinates(path: Path) -> list[tuple]:
    """The triangles of a PLY as sorted tuples of their corners' coordinates, each rotated
    to start at its smallest corner (orientation kept)."""
    from plyfile import PlyData

    ply = PlyData.read(str(path))
    v = np.column_stack([ply["vertex"][c] for c in "xyz"])
    out = []
    for face in ply["face"]["vertex_indices"]:
        corners = [tuple(v[i]) for i in face]
        first = corners.index(min(corners))
        out.append(tuple(corners[first:] + corners[:first]))
    return sorted(out)


def run(capsys, *argv: str) -> str:
    """main(argv)'s standard output (the exit status must be 0)."""
    assert main(list(argv)) == 0, capsys.readouterr().err
    return capsys.readouterr().out


@pytest.fixture
def bunny_piece(tmp_path) -> Path:
    """The lower 40 % (in x) of the Stanford bunny scan, as a .npy file: a piece of a real
    scan, with its spacing, noise and open edges, at a third of the cost."""
    from core.io import read_points

    points = read_points(needed(SHARED / "bunny.ply")).points
    path = tmp_path / "bunny_piece.npy"
    np.save(path, points[points[:, 0] <= np.quantile(points[:, 0], 0.4)])
    return path


def test_export_ply_equals_in_memory(tmp_path, capsys, bunny_piece):
    src = bunny_piece
    tiled, memory = tmp_path / "tiled.ply", tmp_path / "memory.ply"
    line = run(capsys, "export", str(src), "-o", str(tiled), "--alpha", "0.002", "--tiled",
               *SMALL)
    assert "tiled:" in line
    run(capsys, "export", str(src), "-o", str(memory), "--alpha", "0.002")
    assert faces_by_coordinates(tiled) == faces_by_coordinates(memory)


def test_info_json_equals_in_memory(capsys, bunny_piece):
    src = bunny_piece
    tiled = json.loads(run(capsys, "info", str(src), "--alpha", "0.003", "--tiled", "--json",
                           *SMALL))
    memory = json.loads(run(capsys, "info", str(src), "--alpha", "0.003", "--json"))
    assert tiled["tiles"] >= 4
    assert same_info(tiled, memory) == []


def test_geojson_keeps_geographic_coordinates(tmp_path, capsys):
    src = needed(SHARED / "us_airports.csv")
    tiled, memory = tmp_path / "tiled.geojson", tmp_path / "memory.geojson"
    run(capsys, "export", str(src), "-o", str(tiled), "--alpha", "150000", "--tiled",
        "--tile-points", "400")
    run(capsys, "export", str(src), "-o", str(memory), "--alpha", "150000")
    a, b = (json.loads(p.read_text())["features"] for p in (tiled, memory))
    assert [f["properties"]["role"] for f in a] == [f["properties"]["role"] for f in b]
    for fa, fb in zip(a, b, strict=True):
        ga, gb = shapely.geometry.shape(fa["geometry"]), shapely.geometry.shape(fb["geometry"])
        assert ga.equals(gb)
        assert abs(ga.bounds[0]) <= 180  # longitude/latitude, not metres
    assert a[0]["properties"]["area_m2"] == pytest.approx(b[0]["properties"]["area_m2"])


def test_streamed_las_and_vtu(tmp_path, capsys):
    """A LAS file streamed in chunks (not read whole) gives the same VTU blocks."""
    src = needed(CORPUS / "las" / "pdal_autzen_point_format_3.las")
    tiled, memory = tmp_path / "tiled.vtu", tmp_path / "memory.vtu"
    line = run(capsys, "export", str(src), "-o", str(tiled), "--alpha", "40", "--tiled",
               "--sidecar", "--tile-points", "200")
    assert int(line.split("[tiled: ")[1].split()[0].replace(",", "")) >= 2
    run(capsys, "export", str(src), "-o", str(memory), "--alpha", "40", "--sidecar")
    a, b = (json.loads(Path(f"{p}.json").read_text()) for p in (tiled, memory))
    for key in ("n_cells", "n_regular_facets", "n_singular", "dim"):
        assert a[key] == b[key], key
    assert a["volume"] == pytest.approx(b["volume"], rel=1e-9)


def test_tiled_needs_an_alpha(capsys):
    assert main(["info", str(SHARED / "bunny.ply"), "--tiled"]) == 2
    assert "--tiled needs --alpha" in capsys.readouterr().err
    assert main(["info", str(SHARED / "bunny.ply"), "--tile-points", "5"]) == 2
    assert "--tile-points needs --tiled" in capsys.readouterr().err


def test_weighted_file_with_alpha2(tmp_path, capsys):
    rng = np.random.default_rng(4)
    table = np.column_stack([rng.random((3000, 3)), rng.random(3000) * 1e-3])
    src = tmp_path / "balls.csv"
    np.savetxt(src, table, delimiter=",", header="x,y,z,weight", comments="")
    argv = ["info", str(src), "--alpha2", "0.001", "--json"]
    tiled = json.loads(run(capsys, *argv, "--tiled", "--tile-points", "500"))
    memory = json.loads(run(capsys, *argv))
    assert tiled["weighted"] and tiled["tiles"] >= 4
    for name, counts in memory["classes"].items():
        assert tiled["classes"][name] == {**counts, "exterior": None}
    assert tiled["hidden_points"] == memory["hidden_points"]


def test_memory_sizes():
    from app.tiled_cli import memory_size

    assert memory_size("2GiB") == 2 << 30
    assert memory_size("1500MB") == 1_500_000_000
    assert memory_size("4096") == 4096
    with pytest.raises(Exception, match="memory size"):
        memory_size("lots")

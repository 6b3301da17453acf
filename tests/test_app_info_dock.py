"""What the info dock says, on real files: the counts `alphascoop info` prints (the same
numbers and words), the pieces at the opening alpha, and long names that wrap."""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import pytest
from reference import data_dir

from app.cli import main
from app.dataset import load_dataset
from app.info_panel import data_lines
from app.model import ExplorerModel

CORPUS = Path(__file__).resolve().parent / "data" / "corpus"
DATA = data_dir()
needs_data = pytest.mark.skipif(DATA is None, reason="shared real scans absent")


def dock_lines(path: Path) -> list[str]:
    """The info dock's data lines for the file at path, opened as the window opens it."""
    model = ExplorerModel()
    model.set_dataset(load_dataset(path, lambda *_: None))
    return data_lines(model)


@pytest.mark.parametrize("name", ["ply/pcl_cube.ply", "mesh/trimesh_7_8ths_cube.stl",
                                  "pcd/pcl_bun01.pcd"])
def test_dock_counts_are_the_cli_counts(name, qapp, capsys, tmp_path, monkeypatch) -> None:
    """'8 of 24 points read (16 duplicates merged)' in both (the dock said '8 points read,
    8 used' and the merged duplicates on another line)."""
    monkeypatch.setenv("ALPHASCOOP_CACHE_DIR", str(tmp_path / "cache"))
    assert main(["info", str(CORPUS / name), "--json"]) == 0
    load = json.loads(capsys.readouterr().out)["load"]
    lines = dock_lines(CORPUS / name)
    assert f"{load['n_points']:,} of {load['n_read']:,} points read" in lines[1]
    if load["n_duplicates"]:
        assert f"({load['n_duplicates']:,} duplicates merged)" in lines[1]
    assert main(["info", str(CORPUS / name)]) == 0
    assert f"points      {lines[1]}" in capsys.readouterr().out


@needs_data
@pytest.mark.slow
def test_dock_names_the_pieces_at_the_opening(qapp, tmp_path, monkeypatch) -> None:
    """A raw range scan opens in several pieces: the dock says how many, their share and the
    largest ones', and where it opened in spacings, as `alphascoop info` does."""
    monkeypatch.setenv("ALPHASCOOP_CACHE_DIR", str(tmp_path / "cache"))
    lines = dock_lines(DATA / "bun000_rangegrid.ply")
    opening = next(line for line in lines if line.startswith("opens at "))
    assert "spacings: 5 pieces of 41+ points hold 99 % of the points; the largest 88 %" in (
        opening)


def test_a_long_name_wraps(qapp, tmp_path, monkeypatch) -> None:
    """A file name wider than the dock gets break opportunities (it was cut off)."""
    monkeypatch.setenv("ALPHASCOOP_CACHE_DIR", str(tmp_path / "cache"))
    long = tmp_path / "pcl_bun01_the_stanford_bunny_seen_from_one_side_at_low_resolution.pcd"
    shutil.copyfile(CORPUS / "pcd" / "pcl_bun01.pcd", long)
    name = dock_lines(long)[0]
    assert name.count("\u200b") >= 10 and name.replace("\u200b", "") == f"<b>{long.name}</b>"

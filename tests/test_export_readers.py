"""Exports of real scans in the tools users open them with: a VTU that meshio reads as well
as VTK, and a manifold surface whose split points are listed, so that the user knows what a
merge of duplicate vertices (a slicer reading STL) undoes."""

from __future__ import annotations

import csv
from pathlib import Path

import meshio
import numpy as np
import plyfile
import pytest
import pyvista as pv
import trimesh

from app.cli import main
from core.export.vtkxml import text_of

CORPUS = Path(__file__).resolve().parent / "data" / "corpus"
SCANS = ["pcd/pcl_bun01.pcd", "vtk/vtkdata_faults.vtk", "las/laspy_simple.laz"]


@pytest.fixture(autouse=True)
def own_cache(tmp_path, monkeypatch):
    """A private table cache."""
    monkeypatch.setenv("ALPHASCOOP_CACHE_DIR", str(tmp_path / "cache"))


@pytest.mark.parametrize("name", SCANS)
def test_vtu_reads_in_meshio_and_vtk(name, tmp_path, capsys) -> None:
    """meshio reads the whole file, field data included (it stopped at 'Illegal data type
    String'), and finds the cells VTK finds; the text fields read back as text."""
    out = tmp_path / "x.vtu"
    assert main(["export", str(CORPUS / name), "-o", str(out)]) == 0
    mesh = meshio.read(out)
    grid = pv.read(out)
    assert sum(len(block.data) for block in mesh.cells) == grid.n_cells > 0
    assert len(mesh.points) == grid.n_points
    assert text_of(mesh.field_data["source"]) == str(CORPUS / name)
    assert text_of(grid.field_data["source"]) == str(CORPUS / name)
    assert float(mesh.field_data["alpha"].ravel()[0]) == float(grid.field_data["alpha"][0])


def listed(path: Path) -> tuple[np.ndarray, np.ndarray]:
    """((p, 3) points, (p,) copies) of a split-points listing."""
    with open(path, newline="") as handle:
        rows = list(csv.DictReader(handle))
    return (np.array([[float(r[c]) for c in "xyz"] for r in rows]),
            np.array([int(r["copies"]) for r in rows]))


@pytest.mark.parametrize("name", SCANS)
def test_manifold_split_points_are_named(name, tmp_path, capsys) -> None:
    """Exported as a manifold, the points written more than once are counted in the CLI's
    line and listed with their copies; they are exactly the positions repeated in the
    written PLY, and a merge of duplicate vertices (trimesh's STL load) loses those copies."""
    ply = tmp_path / "x.ply"
    assert main(["export", str(CORPUS / name), "-o", str(ply), "--manifold"]) == 0
    line = capsys.readouterr().out
    points, copies = listed(Path(f"{ply}.split-points.csv"))
    assert len(points) > 0
    assert f"the {len(points):,} split points are listed in {ply}.split-points.csv" in line
    assert "merges duplicate vertices" in line
    data = plyfile.PlyData.read(str(ply))
    vertices = np.column_stack([data["vertex"][c] for c in "xyz"]).astype(np.float64)
    unique, counts = np.unique(vertices, axis=0, return_counts=True)
    repeated = unique[counts > 1]
    order = np.lexsort(points.T[::-1])
    np.testing.assert_array_equal(repeated, points[order].astype(vertices.dtype))
    np.testing.assert_array_equal(counts[counts > 1], copies[order])
    stl = tmp_path / "x.stl"
    assert main(["export", str(CORPUS / name), "-o", str(stl), "--manifold"]) == 0
    merged = trimesh.load(stl)  # merges vertices by position, as slicers do
    assert len(merged.vertices) == len(vertices) - int((copies - 1).sum())

"""Readers answer right or refuse with the reason: an E57 whose points leave its declared
bounds, an E57 with a non-UTF-8 name, a (3, n) .npy, "x, y, z" rows, npz bombs against the
memory left, and a VTU padded with a gigabyte of zeros. Inputs derive from corpus files."""

from __future__ import annotations

import os
import subprocess
import sys
import textwrap
import tracemalloc
import zipfile
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest

from core.errors import FileFormatError
from core.io import read_points

CORPUS = Path(__file__).parent / "data" / "corpus"
BUNNY_E57 = CORPUS / "e57" / "libe57_bunnyInt32.e57"
pye57 = pytest.importorskip("pye57")


def test_e57_points_outside_the_declared_bounds_are_refused(tmp_path):
    """The bunny rewritten with 2,651 points at (0,0,0) and its own header (bounds) kept:
    what a damaged file reads as."""
    damaged = tmp_path / "damaged.e57"
    with pye57.E57(str(BUNNY_E57)) as e57, pye57.E57(str(damaged), mode="w") as out:
        data = e57.read_scan_raw(0)
        n = len(data["cartesianX"])
        for axis in "XYZ":
            data[f"cartesian{axis}"] = data[f"cartesian{axis}"].astype(np.float64)
            data[f"cartesian{axis}"][:2651] = 0.0
        header = e57.get_header(0)
        bounds = {f"{a}{end}": getattr(header, f"{a}{end}") for a in "xyz"
                  for end in ("Minimum", "Maximum")}  # the file's own declared bounds
        out.write_scan_raw(data, scan_header=SimpleNamespace(**bounds))
    with pytest.raises(FileFormatError, match=rf"damaged: 2,651 of {n:,} points lie outside the "
                                              r"bounds the file declares"):
        read_points(damaged)
    assert len(read_points(BUNNY_E57).points) == n  # the file itself passes


def test_e57_with_a_name_that_is_not_utf8(tmp_path):
    name = os.fsdecode(os.fsencode(tmp_path) + b"/bunny-\xff\xfe.e57")
    Path(name).write_bytes(BUNNY_E57.read_bytes())
    ps = read_points(name)
    np.testing.assert_array_equal(ps.points, read_points(BUNNY_E57).points)


def test_a_3_by_n_npy_is_transposed_and_said(tmp_path):
    points = read_points(CORPUS / "pcd" / "pcl_bun01.pcd").points
    np.save(tmp_path / "rows.npy", points)
    np.save(tmp_path / "columns.npy", points.T)
    want = read_points(tmp_path / "rows.npy")
    got = read_points(tmp_path / "columns.npy")
    np.testing.assert_array_equal(got.points, want.points)
    assert any("transposed" in note for note in got.report.notes)
    np.savez(tmp_path / "columns.npz", points=points.T, normals=np.ones_like(points).T)
    got = read_points(tmp_path / "columns.npz")
    np.testing.assert_array_equal(got.points, want.points)
    assert got.attributes["normals"].shape == points.shape


def test_rows_with_a_space_after_each_comma(tmp_path):
    """The corpus bunny in millimetres with three decimals ("1.234, 5.678, 9.012"), as
    exporters write it: '1.234,' is no grouped thousand."""
    points = np.round(read_points(CORPUS / "text" / "pdal_bunny_8.pts").points * 1000.0, 3)
    path = tmp_path / "spaced.csv"
    path.write_text("x, y, z\n" + "".join(", ".join(f"{v:.3f}" for v in row) + "\n"
                                          for row in points))
    np.testing.assert_array_equal(read_points(path).points, points)


def _deflated_zeros_table(path: Path, nbytes: int) -> None:
    """An .npz of one float64 member of zeros (what a table's 'points' could be), deflated."""
    n = nbytes // 24
    header = {"descr": "<f8", "fortran_order": False, "shape": (n, 3)}
    with zipfile.ZipFile(path, "w", zipfile.ZIP_DEFLATED) as zf, \
            zf.open("points.npy", "w", force_zip64=True) as member:
        np.lib.format.write_array_header_2_0(member, header)
        chunk = bytes(1 << 20)
        for start in range(0, n * 24, len(chunk)):
            member.write(chunk[: min(len(chunk), n * 24 - start)])


def test_a_table_bomb_beyond_the_memory_limit_is_a_clear_error(tmp_path):
    """In a process whose address space is limited, a table whose arrays would not fit is
    a FileFormatError naming the file, never a MemoryError."""
    path = tmp_path / "bomb.npz"
    _deflated_zeros_table(path, 1536 << 20)  # 1.5 GiB of zeros, about 1.5 MB on disk
    assert path.stat().st_size < 4 << 20
    script = textwrap.dedent(f"""
        import resource, sys
        from core.complex import AlphaComplex
        from core.errors import FileFormatError
        with open("/proc/self/status") as fh:
            size = next(int(l.split()[1]) * 1024 for l in fh if l.startswith("VmSize:"))
        resource.setrlimit(resource.RLIMIT_AS,
                           (size + (768 << 20), resource.getrlimit(resource.RLIMIT_AS)[1]))
        try:
            AlphaComplex.load({str(path)!r})
        except FileFormatError as exc:
            print("refused:", exc)
        from core.storage.memory import available_memory
        assert available_memory() <= 768 << 20
    """)
    run = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                         env={**os.environ, "PYTHONPATH": str(Path(__file__).parents[1])},
                         timeout=300)
    assert run.returncode == 0 and "MemoryError" not in run.stderr, run.stderr
    assert "refused:" in run.stdout and "bomb.npz" in run.stdout and "memory" in run.stdout


def test_a_vtu_padded_with_a_gigabyte_of_zeros_is_refused_before_reading(tmp_path):
    import meshio

    points = read_points(CORPUS / "pcd" / "pcl_bun01.pcd").points
    mesh = meshio.Mesh(points, [("vertex", np.arange(len(points))[:, None])])
    path = tmp_path / "grid.vtu"
    meshio.write(path, mesh, binary=False)
    assert len(read_points(path).points) == len(mesh.points)  # the file itself reads
    os.truncate(path, 1 << 30)  # sparse: a gigabyte of holes after the XML
    tracemalloc.start()
    try:
        with pytest.raises(FileFormatError, match=r"does not end with </VTKFile>"):
            read_points(path)
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert peak < 16 << 20

"""gmsh in two halves (core.backends.split with backend "gmsh": one half in a child process,
core.backends.gmsh_half): the joined cells are Qhull's simplex for simplex, or the build
triangulates in one gmsh call (the reason in the note); the child never outlives its
parent and never sends anything but plain arrays."""

from __future__ import annotations

import io
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest
from reference import DATA_ABSENT, data_dir, read_scan
from test_backends import DEGENERATE, TIED, cell_set, prepared
from test_split import SPLITTABLE, assert_same_cells, by_rows, splits_counted

import core.backends as backends
import core.backends.gmsh_half as gmsh_half
import core.backends.split as split
from core import AlphaComplex
from core.build.delaunay import Triangulation, triangulate

pytestmark = pytest.mark.skipif(not backends.gmsh_backend.installed(),
                                reason="the optional gmsh package is not installed")
ROOT = Path(__file__).resolve().parents[1]


def gmsh_split_equals_qhull(points: np.ndarray) -> Triangulation:
    tri = split.split_triangulation(points, None, "gmsh")
    assert isinstance(tri, Triangulation), tri
    assert_same_cells(tri, triangulate(points))
    return tri


@pytest.mark.parametrize("name", list(SPLITTABLE))
def test_gmsh_split_equals_one_qhull_call(name: str) -> None:
    tri = gmsh_split_equals_qhull(prepared(SPLITTABLE[name](np.random.default_rng(19))))
    assert tri.mirror is not None  # the facet passes read it instead of gathering


@pytest.mark.slow
@pytest.mark.parametrize("name", ["bunny.ply", "bunny_dupverts.stl", "autzen_trim.las"])
def test_gmsh_split_equals_one_qhull_call_on_real_scans(name: str) -> None:
    folder = data_dir()
    if folder is None:
        pytest.skip(DATA_ABSENT)
    gmsh_split_equals_qhull(prepared(read_scan(folder / name)))


@pytest.mark.parametrize("name", TIED)
def test_degenerate_input_falls_back_from_the_gmsh_halves(name: str, monkeypatch) -> None:
    """Lattices, cospherical points (no unique Delaunay triangulation): the gmsh halves cannot
    promise Qhull's cells (the reason in the note), nor can one gmsh call: the automatic
    choice is one Qhull call."""
    points = prepared(DEGENERATE[name](np.random.default_rng(3)))
    monkeypatch.setattr(split, "GMSH_SPLIT_FROM_POINTS", 0)
    monkeypatch.setattr(backends, "GMSH_FROM_POINTS", 0)
    outcomes = splits_counted(monkeypatch)
    tri, choice = backends.delaunay(points, None)
    ref = triangulate(points)
    assert len(outcomes) == 1 and outcomes[0] != "split"  # the halves were tried, and failed
    assert choice.backend == "qhull" and choice.note.startswith("gmsh not used: ")
    assert choice.note.endswith(f"; not split in two halves: {outcomes[0]}")
    assert np.array_equal(tri.cells, ref.cells)
    assert np.array_equal(tri.neighbors, ref.neighbors)


def test_the_automatic_choice_splits_large_inputs(monkeypatch) -> None:
    """From GMSH_SPLIT_FROM_POINTS on, the gmsh build is made in halves (no note), with
    the same table as one gmsh call, bit for bit."""
    points = np.random.default_rng(21).uniform(size=(6000, 3)) * 10.0
    monkeypatch.setattr(backends, "GMSH_FROM_POINTS", 0)
    monkeypatch.setattr(split, "GMSH_SPLIT_FROM_POINTS", 1 << 40)
    outcomes = splits_counted(monkeypatch)
    whole = AlphaComplex.from_points(points)
    calls = []
    original = split._gmsh_halves
    monkeypatch.setattr(split, "_gmsh_halves",
                        lambda *args: calls.append(1) or original(*args))
    monkeypatch.setattr(split, "GMSH_SPLIT_FROM_POINTS", 5000)
    halves = AlphaComplex.from_points(points)
    assert calls and outcomes == ["split"] and halves.build_info.backend == "gmsh"
    assert halves.build_info.backend_note == ""
    for k in range(4):
        (a, ia), (b, ib) = (by_rows(ac.simplices(k), ac.intervals_sq(k))
                            for ac in (whole, halves))
        assert np.array_equal(a, b) and np.array_equal(ia, ib)


def test_a_failed_child_falls_back_to_one_gmsh_call(monkeypatch) -> None:
    """A child that cannot run (here: its interpreter exits at once) gives the reason; the
    build makes one gmsh call and says why."""
    points = prepared(np.random.default_rng(22).uniform(size=(5000, 3)))
    monkeypatch.setattr(gmsh_half.sys, "executable", "/bin/false")
    reason = split.split_triangulation(points, None, "gmsh")
    assert isinstance(reason, str) and reason.startswith("the second half's process failed")
    monkeypatch.setattr(split, "GMSH_SPLIT_FROM_POINTS", 0)
    tri, choice = backends.delaunay(points, "gmsh")
    assert choice == backends.Choice("gmsh", f"not split in two halves: {reason}")
    assert np.array_equal(cell_set(tri.cells), cell_set(triangulate(points).cells))


def test_a_wrong_half_is_caught(monkeypatch) -> None:
    """One flipped edge among a half's kept cells: the half's own check refuses it."""
    points = prepared(np.random.default_rng(23).uniform(size=(3000, 2)))
    original = backends.gmsh_backend.gmsh_cells

    def flipped(coords: np.ndarray) -> np.ndarray:
        cells = original(coords)
        nbrs, _ = backends.facets.neighbours(cells, len(coords))
        t = int(np.flatnonzero((nbrs >= 0).all(axis=1))[len(cells) // 3])
        i = 0
        u = int(nbrs[t, i])
        p, q = cells[t, i], int(np.setdiff1d(cells[u], cells[t])[0])
        x, y = np.delete(cells[t], i)
        cells[t], cells[u] = np.sort([p, q, x]), np.sort([p, q, y])
        return cells

    monkeypatch.setattr(backends.gmsh_backend, "gmsh_cells", flipped)
    low = np.arange(len(points))[points[:, 0] < 0]
    high = np.arange(len(points))[points[:, 0] >= 0]
    reason = split.gmsh_half(points, low, high, 0, True)
    assert isinstance(reason, str) and "not certainly Delaunay" in reason  # the local check


def child_pids(parent: int) -> list[int]:
    """Pids of the half processes whose parent is `parent` (from /proc)."""
    found = []
    for entry in Path("/proc").iterdir():
        if not entry.name.isdigit():
            continue
        try:
            cmdline = (entry / "cmdline").read_bytes()
            ppid = int((entry / "stat").read_text().rsplit(")", 1)[1].split()[1])
        except (OSError, ValueError, IndexError):
            continue
        if ppid == parent and b"core.backends.half_child" in cmdline:
            found.append(int(entry.name))
    return found


@pytest.mark.skipif(not Path("/proc").is_dir(), reason="needs /proc (Linux)")
def test_the_half_process_dies_with_its_parent() -> None:
    """A build killed while its second half is triangulated leaves no process behind (the
    window kills a build process on Cancel)."""
    script = ("import numpy as np; from core.backends.split import split_triangulation; "
              "p = np.random.default_rng(0).uniform(size=(1_500_000, 3)); "
              "print('ready', flush=True); split_triangulation(p, None, 'gmsh')")
    build = subprocess.Popen([sys.executable, "-c", script], cwd=ROOT, stdout=subprocess.PIPE)
    try:
        assert build.stdout.readline().strip() == b"ready"
        deadline = time.monotonic() + 60
        while not (halves := child_pids(build.pid)) and time.monotonic() < deadline:
            time.sleep(0.05)
        assert halves, "the second half's process never started"

        def named() -> bool:  # named once its death signal is set (the same prctl place)
            try:
                return all(Path(f"/proc/{pid}/comm").read_text().strip() == "alphascoop-half"
                           for pid in halves)
            except OSError:
                return False

        while not named() and time.monotonic() < deadline:
            time.sleep(0.05)
        assert named(), "the half process never named itself"
        os.kill(build.pid, signal.SIGKILL)
        build.wait()
        deadline = time.monotonic() + 10
        while any(Path(f"/proc/{pid}").exists() for pid in halves) and \
                time.monotonic() < deadline:
            time.sleep(0.05)
        alive = [pid for pid in halves if Path(f"/proc/{pid}").exists()
                 and "Z" not in (Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1][:3])]
        assert not alive, f"half processes {alive} outlived their killed parent"
    finally:
        if build.poll() is None:
            build.kill()
            build.wait()


def test_arrays_cross_the_pipe_unchanged() -> None:
    stream = io.BytesIO()
    arrays = {"a": np.arange(12, dtype=np.int32).reshape(4, 3), "b": np.zeros(0, np.int8),
              "c": np.linspace(0, 1, 5), "d": np.array([True, False])}
    gmsh_half.send_arrays(stream, arrays, reason="", axis=2)
    stream.seek(0)
    fields, back = gmsh_half.receive_arrays(stream)
    assert fields == {"reason": "", "axis": 2}
    assert set(back) == set(arrays)
    for name, array in arrays.items():
        assert back[name].dtype == array.dtype and np.array_equal(back[name], array)


@pytest.mark.parametrize("damage", ["truncated", "object dtype", "no header"])
def test_a_damaged_stream_is_refused(damage: str) -> None:
    """Never an object array (nothing from the pipe is unpickled), never a short array."""
    stream = io.BytesIO()
    gmsh_half.send_arrays(stream, {"a": np.arange(100, dtype=np.int64)})
    data = stream.getvalue()
    if damage == "truncated":
        data = data[:-8]
    elif damage == "object dtype":
        data = data.replace(b'"<i8"', b'"|O"')
    else:
        data = data.replace(b"\n", b" ", 1)
    with pytest.raises(ValueError):
        gmsh_half.receive_arrays(io.BytesIO(data))


def test_a_halfs_arrays_are_checked_before_they_are_joined() -> None:
    """What the half's process sends must be int32 cells of the points with their neighbour
    rows and int8 mirror, or the build falls back (never an index error later)."""
    cells = np.array([[0, 1, 2, 3], [1, 2, 3, 4]], dtype=np.int32)
    nbrs = np.array([[1, -1, -1, -1], [-1, -1, -1, 0]], dtype=np.int32)
    mirror = np.array([[3, -1, -1, -1], [-1, -1, -1, 0]], dtype=np.int8)
    good = {"cells": cells, "nbrs": nbrs, "mirror": mirror}
    assert split._fits(good, 5, 4)
    assert not split._fits(good, 4, 4)  # a point id out of range
    assert not split._fits(good, 5, 3)  # the wrong dimension
    assert not split._fits({**good, "nbrs": nbrs + 5}, 5, 4)  # a neighbour out of range
    assert not split._fits({**good, "cells": cells.astype(np.int64)}, 5, 4)
    assert not split._fits({**good, "mirror": mirror[:1]}, 5, 4)
    assert not split._fits({"cells": cells, "nbrs": nbrs}, 5, 4)


def test_the_half_process_answers_a_reason_for_damaged_input() -> None:
    """A damaged input makes the half's process answer why (for the build's note and its
    fallback), not print a traceback on the user's terminal."""
    child = subprocess.Popen([sys.executable, "-m", "core.backends.half_child", str(os.getpid())],
                             cwd=ROOT, stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                             stderr=subprocess.PIPE)
    out, err = child.communicate(b'{"fields": {}, "arrays": [["points", "|O", [3]]]}\n',
                                 timeout=60)
    fields, arrays = gmsh_half.receive_arrays(io.BytesIO(out))
    assert child.returncode == 0 and arrays == {}
    assert fields["reason"].startswith("the second half failed (ValueError: unexpected array")
    assert b"Traceback" not in err

"""COPC files in a tiled run are read by their octree: found by their VLR, each tile reads
only the nodes meeting its box, with the rows and tiles the streamed pass gives, and the
result is the in-memory one; a damaged file is one line and leaves no tile file."""

from __future__ import annotations

import contextlib
import os
import shutil
import socket
import struct
import subprocess
import sys
from pathlib import Path

import laspy
import numpy as np
import pytest

from app.cli import main
from app.tiled_cli import las_source
from core import AlphaComplex
from core.errors import FileFormatError
from core.io import read_points
from core.tiled.copc import CopcSource
from core.tiled.memory import query
from core.tiled.partition import read_tile, tile_folder
from core.tiled.runner import (
    RunOptions,
    RunReport,
    partition_source,
    plan_source,
    tiled_run,
)
from core.tiled.sources import LasSource, survey
from tests.tiled_reference import differences, mid_gap_alpha

pytest.importorskip("distributed")

ROOT = Path(__file__).resolve().parents[1]
LAS = ROOT / "tests" / "data" / "corpus" / "las"
#: laspy's test COPC files: one hierarchy page, and the same points with a child page.
COPC = [LAS / "laspy_simple.copc.laz", LAS / "laspy_simple_with_page.copc.laz"]


def file_points(path: Path) -> np.ndarray:
    """(n, 3) the file's points in file order, as laspy reads the whole file."""
    las = laspy.read(str(path))
    return np.column_stack([np.asarray(las.x), np.asarray(las.y), np.asarray(las.z)])


def test_detected_by_its_vlr_not_its_name(tmp_path):
    renamed = tmp_path / "scan.laz"
    shutil.copy(COPC[0], renamed)
    plain = tmp_path / "plain.copc.laz"
    shutil.copy(LAS / "laspy_simple.laz", plain)
    assert isinstance(las_source(renamed), CopcSource)
    assert isinstance(las_source(COPC[1]), CopcSource)
    assert isinstance(las_source(plain), LasSource)


@pytest.mark.parametrize("path", COPC, ids=lambda p: p.name)
def test_in_memory_readers_open_copc_as_laz(path):
    points = read_points(path).points
    np.testing.assert_array_equal(points, file_points(path))


@pytest.mark.parametrize("path", COPC, ids=lambda p: p.name)
def test_rows_are_the_files_rows(path):
    """Streamed node by node, the points come in file order; a box's points carry their
    file rows, and those inside the box are the ones laspy's CopcReader.query returns."""
    source, expected = CopcSource.open(path, chunk=100), file_points(path)
    np.testing.assert_array_equal(np.concatenate([c for c, _ in source.chunks()]), expected)
    lo = expected.min(axis=0) + np.array([500.0, 700.0, -1.0])
    hi = lo + np.array([800.0, 900.0, 1000.0])
    rows, coords = source.box(lo, hi)
    assert np.all(np.diff(rows) > 0) and len(rows) < len(expected)
    np.testing.assert_array_equal(coords, expected[rows])
    inside = np.all((lo <= coords) & (coords <= hi), axis=1)
    with laspy.CopcReader.open(str(path)) as reader:
        found = reader.query(laspy.copc.Bounds(lo, hi))
    theirs = np.column_stack([np.asarray(found.x), np.asarray(found.y), np.asarray(found.z)])
    assert 0 < len(theirs) == inside.sum()
    np.testing.assert_array_equal(np.sort(coords[inside], axis=0), np.sort(theirs, axis=0))


def test_boxes_with_nodes_kept_between_reads():
    """Random boxes one after another (coarse nodes kept between reads, few enough points
    kept that some are let go): every box gives its nodes' points with their file rows."""
    source, expected = CopcSource.open(COPC[0], chunk=150), file_points(COPC[0])
    extent = np.ptp(expected, axis=0)
    rng = np.random.default_rng(5)
    for _ in range(60):
        lo = expected.min(axis=0) + rng.random(3) * extent
        rows, coords = source.box(lo, lo + rng.random(3) * extent / 3)
        np.testing.assert_array_equal(coords, expected[rows])
        assert np.all(np.diff(rows) > 0)
        assert sum(len(c) for c in source.kept.values()) <= 150


def test_tiles_read_by_box_are_the_streamed_tiles(tmp_path):
    """The same plan partitioned by the streamed pass (plain LAZ reader) and by box through
    the octree: the same tiles, each with the same rows, coordinates and core points; and
    no box read the whole file."""
    copc, streamed = CopcSource.open(COPC[1]), LasSource(COPC[1], chunk=100)
    q, options = query(alpha=60.0), RunOptions(tile_points=120)
    seen, indexed = survey(streamed), survey(copc)
    assert indexed.count == seen.count and copc.index_holds
    np.testing.assert_array_equal(np.r_[indexed.lo, indexed.hi], np.r_[seen.lo, seen.hi])
    plan = plan_source(streamed, seen, q, options, 1, 1 << 30)
    report = RunReport()
    ours = partition_source(copc, plan, tmp_path / "box", options, seen.count, report)
    theirs = partition_source(streamed, plan, tmp_path / "streamed", options, seen.count)
    assert ours == theirs and len(ours) >= 8
    for tile in ours:
        a = read_tile(tile_folder(tmp_path / "box", tile), 3, False)
        b = read_tile(tile_folder(tmp_path / "streamed", tile), 3, False)
        for x, y in zip(a[:3], b[:3], strict=True):
            np.testing.assert_array_equal(x, y)
    assert len(report.read) == plan.n_tiles
    assert max(report.read.values()) < seen.count


def test_tiled_run_equals_in_memory(tmp_path):
    points = file_points(COPC[0])
    ac = AlphaComplex.from_points(points)
    at = {"alpha": mid_gap_alpha(ac, 0.6)}
    report = RunReport()
    options = RunOptions(workers=1, memory_per_worker=1 << 30, tile_points=100,
                         scratch=tmp_path)
    merged = tiled_run(las_source(COPC[0]), query(**at), options, report)
    assert differences(ac, merged, at) == []
    assert merged.n_tiles >= 8
    assert max(report.read.values()) < len(points)  # each tile read part of the file
    assert list(tmp_path.iterdir()) == []


def test_points_outside_their_node_stream_as_plain_laz(tmp_path):
    """A hierarchy that puts a node in another cell of its level (its points then lie
    outside its box): the boxes would miss them, so the run streams the file as a plain
    LAZ (no box read) and still equals the in-memory result."""
    data = bytearray(COPC[0].read_bytes())
    with laspy.open(str(COPC[0])) as reader:
        info = next(v for v in reader.header.vlrs if isinstance(v, laspy.copc.CopcInfoVlr))
    entry = np.dtype([("key", "<i4", 4), ("offset", "<u8"), ("size", "<i4"),
                      ("count", "<i4")])  # COPC 1.0's hierarchy entry
    start = info.hierarchy_root_offset
    page = np.frombuffer(bytes(data[start:start + info.hierarchy_root_size]), entry).copy()
    node = int(np.flatnonzero((page["key"][:, 0] == 3) & (page["count"] > 0))[0])
    page["key"][node, 1:3] = 7 - page["key"][node, 1:3]
    data[start:start + info.hierarchy_root_size] = page.tobytes()
    path = tmp_path / "moved.copc.laz"
    path.write_bytes(bytes(data))
    points = file_points(path)
    ac = AlphaComplex.from_points(points)
    at = {"alpha": mid_gap_alpha(ac, 0.6)}
    source, report = las_source(path), RunReport()
    assert isinstance(source, CopcSource)
    merged = tiled_run(source, query(**at), RunOptions(workers=1, memory_per_worker=1 << 30,
                                                       tile_points=100), report)
    assert differences(ac, merged, at) == []
    assert not source.index_holds and report.read == {}


def damaged_copies(tmp_path: Path) -> dict[str, Path]:
    """Copies of a COPC file cut short, with a wrong count in the hierarchy, with a chunk
    moved outside the file, and with garbage in a chunk's compressed bytes."""
    data = COPC[0].read_bytes()
    with laspy.open(str(COPC[0])) as reader:
        root = next(v for v in reader.header.vlrs if isinstance(v, laspy.copc.CopcInfoVlr)
                    ).hierarchy_root_offset
    count, chunk, garbage = bytearray(data), bytearray(data), bytearray(data)
    struct.pack_into("<i", count, root + 28, 999)  # the first entry's point count
    struct.pack_into("<Q", chunk, root + 16, len(data) + 10)  # the first entry's offset
    garbage[5000:9000] = np.random.default_rng(3).integers(0, 256, 4000, np.uint8).tobytes()
    out = {}
    for name, body in (("truncated", data[: len(data) - 700]), ("count", count),
                       ("offset", chunk), ("chunk", garbage)):
        out[name] = tmp_path / f"{name}.copc.laz"
        out[name].write_bytes(bytes(body))
    return out


def test_damaged_copc_is_one_line(tmp_path, capsys, monkeypatch):
    monkeypatch.setenv("ALPHASCOOP_CACHE_DIR", str(tmp_path / "cache"))
    scratch = tmp_path / "scratch"
    for name, path in damaged_copies(tmp_path).items():
        code = main(["info", str(path), "--alpha", "60", "--tiled", "--tile-points", "100",
                     "--scratch", str(scratch)])
        err = capsys.readouterr().err.strip()
        assert code == 1, name
        assert len(err.splitlines()) == 1 and "COPC" in err, (name, err)
        assert not scratch.exists() or list(scratch.iterdir()) == [], name


def test_damage_found_while_the_cluster_starts_is_one_line(tmp_path):
    """A bad chunk is found after the local cluster began to start, with distributed's
    default HTTP port 8787 taken (as by another cluster): the process's stderr is the one
    line still (distributed warned of the port there)."""
    path = damaged_copies(tmp_path)["chunk"]
    env = {**os.environ, "ALPHASCOOP_CACHE_DIR": str(tmp_path / "cache"),
           "PYTHONPATH": str(ROOT)}
    with socket.socket() as busy:
        with contextlib.suppress(OSError):  # already taken: the case itself
            busy.bind(("127.0.0.1", 8787))
            busy.listen()
        result = subprocess.run(
            [sys.executable, "-m", "app", "info", str(path), "--alpha", "60", "--tiled",
             "--tile-points", "100", "--scratch", str(tmp_path / "scratch")],
            capture_output=True, text=True, env=env, cwd=tmp_path, timeout=120)
    assert result.returncode == 1
    assert result.stderr.startswith("alphascoop: error: ")
    assert len(result.stderr.strip().splitlines()) == 1, result.stderr
    assert list((tmp_path / "scratch").iterdir()) == []


def test_damage_met_while_reading_tiles_leaves_no_tile_file(tmp_path):
    """The file goes bad after the first tiles were written: one FileFormatError, and the
    scratch folder holds nothing afterwards."""
    path = tmp_path / "scan.copc.laz"
    shutil.copy(COPC[0], path)
    source = CopcSource.open(path)
    first = int(source.octree.offset.min())

    def progress(fraction: float, stage: str) -> None:
        if "COPC index" in stage:
            with open(path, "r+b") as fh:  # every chunk's bytes zeroed
                fh.seek(first)
                fh.write(bytes(int(source.octree.offset.max()) - first))

    options = RunOptions(workers=1, memory_per_worker=1 << 30, tile_points=100,
                         scratch=tmp_path / "scratch", progress=progress)
    with pytest.raises(FileFormatError, match="damaged COPC") as caught:
        tiled_run(source, query(alpha=60.0), options)
    assert len(str(caught.value).splitlines()) == 1
    assert list((tmp_path / "scratch").iterdir()) == []

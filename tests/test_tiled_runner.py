"""The Dask runner: equal to the in-memory tiles, a failed tile named, cancel cleans up, and a
real cluster of separate `dask scheduler` / `dask worker` processes."""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

from core import AlphaComplex
from core.errors import Cancelled
from core.tiled.memory import query
from core.tiled.runner import (
    RunOptions,
    RunReport,
    TileError,
    partition_source,
    plan_source,
    run_tiles,
    tiled_run,
)
from core.tiled.sources import ArraySource, survey
from tests.tiled_reference import differences

pytest.importorskip("distributed")

#: Seconds the separate scheduler and worker processes get to come up.
CLUSTER_START_S = 60


def cloud(n: int = 6000) -> np.ndarray:
    return np.random.default_rng(21).random((n, 3))


def test_runner_equals_in_memory(tmp_path, monkeypatch):
    for name in ("OMP_NUM_THREADS", "MALLOC_TRIM_THRESHOLD_"):  # what the nannies set
        monkeypatch.delenv(name, raising=False)
    environ = dict(os.environ)
    points, at = cloud(), {"alpha": 0.05}
    report = RunReport()
    options = RunOptions(workers=2, memory_per_worker=1 << 30, tile_points=800,
                         scratch=tmp_path)
    merged = tiled_run(ArraySource.from_points(points, chunk=1000), query(**at), options,
                       report)
    assert differences(AlphaComplex.from_points(points), merged, at) == []
    assert len(report.tiles) == merged.n_tiles >= 6
    assert list(tmp_path.iterdir()) == []  # the scratch folder is gone
    assert dict(os.environ) == environ  # later child processes get this process's settings


def test_failed_tile_is_named(tmp_path):
    from distributed import Client, LocalCluster

    source = ArraySource.from_points(cloud(3000))
    q, options = query(alpha=0.05), RunOptions(tile_points=500, retries=1)
    seen = survey(source)
    plan = plan_source(source, seen, q, options, 1, 1 << 30)
    tiles = partition_source(source, plan, tmp_path, options, seen.count)
    broken = tiles[len(tiles) // 2]
    part = next((tmp_path / "tiles" / f"t{broken:07d}").glob("c*.npy"))
    part.write_bytes(b"not an array")
    with LocalCluster(n_workers=1, processes=False, threads_per_worker=1,
                      dashboard_address=None) as cluster, Client(cluster) as client:
        with pytest.raises(TileError, match=f"tile {broken} .*failed after retrying"):
            run_tiles(client, tiles, plan, tmp_path, 3, False, q, options, RunReport())
        assert not (tmp_path / "results" / f"t{broken:07d}.npz").exists()


def test_tile_task_builds_unsplit_on_one_core(tmp_path, monkeypatch):
    """A worker's tile takes one core (the cluster's other workers have the others): its
    build runs unsplit, and the answer is the in-process tile's."""
    from core.parallel import in_unsplit
    from core.tiled import runner
    from core.tiled.partition import read_tile, tile_folder
    from core.tiled.result import TileResult

    source = ArraySource.from_points(cloud(3000))
    q, options = query(alpha=0.05), RunOptions(tile_points=1000)
    seen = survey(source)
    plan = plan_source(source, seen, q, options, 1, 1 << 30)
    tile = partition_source(source, plan, tmp_path, options, seen.count)[0]
    seen_unsplit, real = [], runner.compute_tile

    def compute(*args):
        seen_unsplit.append(in_unsplit())
        return real(*args)

    monkeypatch.setattr(runner, "compute_tile", compute)
    out = tmp_path / "t.npz"
    cost = runner.tile_task(str(tile_folder(tmp_path, tile)), str(out), 3, False, q.at)
    assert seen_unsplit == [True] and not in_unsplit()
    assert cost["cpu_seconds"] > 0 and cost["points"] > 0
    with np.load(out, allow_pickle=False) as arrays:
        got = TileResult.from_arrays({k: arrays[k] for k in arrays.files})
    expected = real(*read_tile(tile_folder(tmp_path, tile), 3, False), q.at, 3)
    for a, b in zip(got.simplices, expected.simplices, strict=True):
        assert np.array_equal(a, b)


def test_local_workers_keep_the_default_malloc_threshold(tmp_path):
    """distributed's MALLOC_TRIM_THRESHOLD_ (a fixed mmap threshold: every large temporary
    mapped anew) is not passed to the local cluster's workers. The nannies' settings for
    their workers (OMP_NUM_THREADS=1 and the like) are taken out of this process after, as
    tiled_run does, so no later test's child process inherits them."""
    from core.tiled.runner import client_for, close_client, restore_environment

    environ = dict(os.environ)
    client = client_for(RunOptions(), 1, 1 << 30, tmp_path)
    try:
        values = client.run(lambda: os.environ.get("MALLOC_TRIM_THRESHOLD_"))
    finally:
        close_client(client, RunOptions())
        restore_environment(environ)
    assert list(values.values()) == [None]


def test_cancel_removes_scratch(tmp_path):
    def progress(fraction: float, stage: str) -> None:
        if stage.startswith("tiles"):
            raise Cancelled("cancelled")

    options = RunOptions(workers=1, memory_per_worker=1 << 30, tile_points=500,
                         scratch=tmp_path, progress=progress)
    with pytest.raises(Cancelled):
        tiled_run(ArraySource.from_points(cloud(3000)), query(alpha=0.05), options)
    assert list(tmp_path.iterdir()) == []


def test_a_file_changed_while_read_is_refused(tmp_path):
    """A file that grows between the passes (its tiles planned from the first) is refused in
    one line, with nothing left in the scratch folder."""
    from core.errors import FileFormatError
    from core.io.streams import TextSource

    path = tmp_path / "growing.xyz"
    path.write_text("\n".join(" ".join(repr(v) for v in p) for p in cloud(3000).tolist()))
    passes = []

    class Growing(TextSource):
        def chunks(self):
            passes.append(1)
            yield from super().chunks()
            if len(passes) == 2:  # after the density pass, before the partition
                with open(self.path, "a") as fh:
                    fh.write("\n0.5 0.5 0.5\n")

    scratch = tmp_path / "scratch"
    options = RunOptions(workers=1, memory_per_worker=1 << 30, tile_points=500,
                         scratch=scratch)
    with pytest.raises(FileFormatError, match="changed while it was read"):
        tiled_run(Growing.open(path, chunk=1000), query(alpha=0.05), options)
    assert len(passes) == 3 and list(scratch.iterdir()) == []


def _wait_for(path: Path, process: subprocess.Popen, seconds: float) -> None:
    """Wait until `path` exists (the process must stay alive); fail after `seconds`."""
    end = time.monotonic() + seconds
    while not path.exists():
        assert process.poll() is None, f"exited with status {process.returncode}"
        assert time.monotonic() < end, f"{path} did not appear within {seconds} s"
        time.sleep(0.2)


@pytest.mark.timeout(400)
def test_separate_scheduler_and_worker_processes(tmp_path, capsys):
    """`dask scheduler` and two `dask worker` processes on 127.0.0.1; the CLI's --scheduler
    run over a shared --scratch folder equals the in-memory info."""
    from app.cli import main

    dask = shutil.which("dask", path=os.path.dirname(sys.executable))
    assert dask is not None, "the dask command comes with the tiled extra"
    env = {**os.environ, "PYTHONPATH": str(Path(__file__).resolve().parents[1])}
    info = tmp_path / "scheduler.json"
    scheduler = subprocess.Popen([dask, "scheduler", "--host", "127.0.0.1", "--port", "0",
                                  "--no-dashboard", "--scheduler-file", str(info)], env=env,
                                 stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    workers: list[subprocess.Popen] = []
    try:
        _wait_for(info, scheduler, CLUSTER_START_S)
        address = json.loads(info.read_text())["address"]
        for _ in range(2):
            workers.append(subprocess.Popen(
                [dask, "worker", address, "--host", "127.0.0.1", "--nthreads", "1",
                 "--nworkers", "1", "--memory-limit", "1GiB", "--no-dashboard"], env=env,
                stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL))
        points = cloud(5000)
        src = tmp_path / "cloud.xyz"
        np.savetxt(src, points)
        scratch = tmp_path / "shared"
        assert main(["info", str(src), "--alpha", "0.06", "--tiled", "--json",
                     "--scheduler", address, "--scratch", str(scratch),
                     "--tile-points", "700"]) == 0
        tiled = json.loads(capsys.readouterr().out)
        assert main(["info", str(src), "--alpha", "0.06", "--json"]) == 0
        memory = json.loads(capsys.readouterr().out)
        assert tiled["tiles"] >= 6
        for name, counts in memory["classes"].items():
            assert tiled["classes"][name] == {**counts, "exterior": None}
        assert tiled["volume"] == pytest.approx(memory["volume"], rel=1e-9)
        assert list(scratch.iterdir()) == []
    finally:
        for process in [*workers, scheduler]:
            process.terminate()
        for process in [*workers, scheduler]:
            try:
                process.wait(timeout=20)
            except subprocess.TimeoutExpired:
                process.kill()
                process.wait()

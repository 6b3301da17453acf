"""Temporary files of writes: named as ours, cleaned when their writer is gone, never results."""

from __future__ import annotations

import os
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import numpy as np
import pytest

from core import AlphaComplex
from core.cache import entry_path, is_cached, load_cached, prune, store
from core.export import write_table
from core.storage.atomic import (
    atomic_write,
    is_temporary,
    remove_stale_temporaries,
    temporary_name,
)

ROOT = Path(__file__).resolve().parents[1]
HOUR = 3600.0


@pytest.fixture
def cache(tmp_path, monkeypatch):
    folder = tmp_path / "cache"
    monkeypatch.setenv("ALPHASCOOP_CACHE_DIR", str(folder))
    return folder


@pytest.fixture(scope="module")
def dead_pid() -> int:
    """The id of a process that has ended (and was reaped)."""
    child = subprocess.Popen([sys.executable, "-c", "pass"])
    child.wait()
    return child.pid


@pytest.fixture(scope="module")
def ac():
    return AlphaComplex.from_points(np.random.default_rng(2).normal(size=(60, 3)))


def make_temporary(folder: Path, target: str, pid: int, age: float = 0.0, host=None) -> Path:
    """A temporary file as a writer with `pid` would name it, last written `age` s ago."""
    path = folder / temporary_name(folder / target, pid=pid, host=host)
    path.write_bytes(b"partial")
    then = time.time() - age
    os.utime(path, (then, then))
    return path


def test_temporary_names_say_whose_they_are(tmp_path):
    seen = []
    atomic_write(tmp_path / "bunny.ply", lambda fh: seen.extend(os.listdir(tmp_path)))
    assert len(seen) == 1 and is_temporary(seen[0])
    assert seen[0].startswith(".bunny.ply.alphascoop-tmp-") and seen[0].endswith(".ply")
    assert f"-{os.getpid()}-" in seen[0]
    assert os.listdir(tmp_path) == ["bunny.ply"]
    for other in ("bunny.ply", ".bunny.ply", "bunny.alphascoop-tmp-1.ply", ".hidden.tmp.ply"):
        assert not is_temporary(other)


def test_stale_temporaries_are_removed_and_nothing_else(tmp_path, dead_pid):
    dead = make_temporary(tmp_path, "a.ply", dead_pid)
    alive = make_temporary(tmp_path, "b.ply", os.getpid())
    old_alive = make_temporary(tmp_path, "c.ply", os.getpid(), age=48 * HOUR)
    legacy_old = tmp_path / ".d.0123456789ab.tmp.ply"
    legacy_new = tmp_path / ".e.0123456789ab.tmp.ply"
    for path, age in ((legacy_old, 2 * HOUR), (legacy_new, 0.0)):
        path.write_bytes(b"partial")
        os.utime(path, (time.time() - age,) * 2)
    users = [tmp_path / n for n in (".d.tmp.ply", "a.ply", ".a.ply.alphascoop-tmp-notes.txt")]
    for path in users:
        path.write_bytes(b"the user's")
        os.utime(path, (time.time() - 99 * HOUR,) * 2)
    (tmp_path / f".x.ply.alphascoop-tmp-abcdef-{dead_pid}-0123abcd.ply").mkdir()  # not a file
    assert remove_stale_temporaries(tmp_path) == 3
    left = {p.name for p in tmp_path.iterdir()}
    assert dead.name not in left and old_alive.name not in left and legacy_old.name not in left
    assert {alive.name, legacy_new.name, *(p.name for p in users)} <= left


def test_other_machines_temporaries_wait_for_the_age_limit(tmp_path, dead_pid):
    young = make_temporary(tmp_path, "a.ply", dead_pid, host="f00f00")
    old = make_temporary(tmp_path, "b.ply", dead_pid, age=2 * HOUR, host="f00f00")
    remove_stale_temporaries(tmp_path)
    assert young.exists() and not old.exists()


def test_next_export_to_the_folder_cleans_up_after_a_killed_one(tmp_path, ac):
    script = textwrap.dedent("""
        import sys, time
        import numpy as np
        import core.export.table as tables
        from core import AlphaComplex
        from core.export import write_table

        def stuck(path, ac):
            path.write_bytes(b"x" * 100_000)
            print("writing", flush=True)
            time.sleep(600)

        tables.TABLE_WRITERS[".npz"] = stuck
        ac = AlphaComplex.from_points(np.random.default_rng(0).random((30, 3)))
        write_table(ac, sys.argv[1])
    """)
    child = subprocess.Popen([sys.executable, "-c", script, str(tmp_path / "t.npz")],
                             stdout=subprocess.PIPE, text=True, cwd=ROOT,
                             env={**os.environ, "PYTHONPATH": str(ROOT)})
    try:
        assert child.stdout.readline().strip() == "writing"
    finally:
        child.kill()
        child.wait()
        child.stdout.close()
    left = [p.name for p in tmp_path.iterdir()]
    assert len(left) == 1 and is_temporary(left[0]), "the killed export left its temporary"
    write_table(ac, tmp_path / "other.npz")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["other.npz"]


def test_killed_cache_store_is_cleaned_on_open_and_in_prune(cache, dead_pid, ac):
    cache.mkdir()
    points = np.random.default_rng(7).random((40, 3))
    key = entry_path(points).name
    for age in (0.0, 0.0):
        make_temporary(cache, key, dead_pid, age=age)
    legacy = cache / f".{key[:-4]}.0123456789ab.tmp.npz"
    legacy.write_bytes(b"partial")
    os.utime(legacy, (time.time() - 2 * HOUR,) * 2)
    assert not is_cached(points) and load_cached(points) is None
    assert list(cache.iterdir()) == [], "opening cleans the cache folder"
    make_temporary(cache, key, dead_pid)
    prune(cache)
    assert list(cache.iterdir()) == [], "prune cleans it too"


def test_a_running_store_is_not_a_result_and_is_left_alone(cache, ac):
    cache.mkdir()
    points = np.asarray(ac.points)
    live = make_temporary(cache, entry_path(points).name, os.getpid())
    assert not is_cached(points) and load_cached(points) is None
    prune(cache, max_bytes=0)
    assert live.exists()
    assert store(ac, points) == entry_path(points) and is_cached(points)
    assert live.exists()

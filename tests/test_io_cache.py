"""The table cache: a second build is a load, a corrupt entry is rebuilt, never an error."""

from __future__ import annotations

import numpy as np
import pytest

from core import AlphaComplex
from core.cache import build_cached, entry_path, is_cached, points_key, prune


@pytest.fixture
def cache(tmp_path, monkeypatch):
    """A private cache folder."""
    folder = tmp_path / "cache"
    monkeypatch.setenv("ALPHASCOOP_CACHE_DIR", str(folder))
    return folder


@pytest.fixture
def points() -> np.ndarray:
    """(200, 3) random points."""
    return np.random.default_rng(4).normal(size=(200, 3))


def test_second_build_comes_from_cache(cache, points):
    first = build_cached(points)
    assert is_cached(points)
    stages = []
    second = build_cached(points, progress=lambda f, s: stages.append(s))
    assert stages == ["loaded from cache"]
    for k in range(4):
        np.testing.assert_array_equal(second.simplices(k), first.simplices(k))
        np.testing.assert_array_equal(second.intervals(k), first.intervals(k))


def test_no_cache_neither_reads_nor_writes(cache, points):
    build_cached(points, use_cache=False)
    assert not is_cached(points)


@pytest.mark.parametrize("junk", [b"", b"PK\x03\x04 broken zip", b"\x93NUMPY garbage"])
def test_corrupt_entry_is_rebuilt(cache, points, junk):
    entry = entry_path(points)
    entry.parent.mkdir(parents=True)
    entry.write_bytes(junk)
    ac = build_cached(points)
    assert isinstance(ac, AlphaComplex) and len(ac.points) == 200
    assert entry.stat().st_size > 1000  # replaced by a good table


def test_entry_for_other_points_is_rebuilt(cache, points):
    other = AlphaComplex.from_points(points[:50])
    entry = entry_path(points)
    entry.parent.mkdir(parents=True)
    other.save(entry)
    assert len(build_cached(points).input_index) == 200


def test_unwritable_cache_still_builds(tmp_path, monkeypatch, points):
    blocker = tmp_path / "file"
    blocker.write_text("not a folder")
    monkeypatch.setenv("ALPHASCOOP_CACHE_DIR", str(blocker / "cache"))
    assert len(build_cached(points).points) == 200


def test_key_depends_on_values_and_shape(points):
    assert points_key(points) == points_key(points.copy())
    moved = points.copy()
    moved[0, 0] = np.nextafter(moved[0, 0], np.inf)
    assert points_key(moved) != points_key(points)
    assert points_key(points[:, :2]) != points_key(points.reshape(-1, 2)[:200])


def test_prune_keeps_newest(tmp_path):
    import os

    for i in range(5):
        (tmp_path / f"{i}.npz").write_bytes(b"x" * 100)
        os.utime(tmp_path / f"{i}.npz", (i, i))
    prune(tmp_path, max_bytes=250)
    assert sorted(p.name for p in tmp_path.glob("*.npz")) == ["3.npz", "4.npz"]

"""The table cache: a second build is a load, a corrupt entry is rebuilt, never an error."""

from __future__ import annotations

import numpy as np
import pytest

from core import AlphaComplex
from core.cache import MAX_CACHE_BYTES, cache_limit, entry_path, is_cached, points_key, prune
from core.obtain import obtain


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
    first = obtain(points)
    assert is_cached(points) and first.source == "built" and first.entry == entry_path(points)
    stages = []
    second = obtain(points, progress=lambda f, s: stages.append(s))
    assert stages == ["loaded from cache"] and second.source == "cache"
    first, second = first.complex, second.complex
    for k in range(4):
        np.testing.assert_array_equal(second.simplices(k), first.simplices(k))
        np.testing.assert_array_equal(second.intervals(k), first.intervals(k))


def test_no_cache_neither_reads_nor_writes(cache, points):
    obtained = obtain(points, use_cache=False)
    assert not is_cached(points) and obtained.source == "built" and obtained.entry is None


@pytest.mark.parametrize("junk", [b"", b"PK\x03\x04 broken zip", b"\x93NUMPY garbage"])
def test_corrupt_entry_is_rebuilt(cache, points, junk):
    entry = entry_path(points)
    entry.parent.mkdir(parents=True)
    entry.write_bytes(junk)
    obtained = obtain(points)
    assert obtained.source == "rebuilt"
    assert isinstance(obtained.complex, AlphaComplex) and len(obtained.complex.points) == 200
    assert entry.stat().st_size > 1000  # replaced by a good table


def test_entry_for_other_points_is_rebuilt(cache, points):
    other = AlphaComplex.from_points(points[:50])
    entry = entry_path(points)
    entry.parent.mkdir(parents=True)
    other.save(entry)
    obtained = obtain(points)
    assert len(obtained.complex.input_index) == 200 and obtained.source == "rebuilt"
    assert obtain(points).source == "cache"  # the rebuilt entry replaced the wrong one


def test_unwritable_cache_still_builds(tmp_path, monkeypatch, points):
    blocker = tmp_path / "file"
    blocker.write_text("not a folder")
    monkeypatch.setenv("ALPHASCOOP_CACHE_DIR", str(blocker / "cache"))
    obtained = obtain(points)
    assert len(obtained.complex.points) == 200 and obtained.source == "built"
    assert obtained.entry is None


def test_key_depends_on_values_and_shape(points):
    assert points_key(points) == points_key(points.copy())
    moved = points.copy()
    moved[0, 0] = np.nextafter(moved[0, 0], np.inf)
    assert points_key(moved) != points_key(points)
    assert points_key(points[:, :2]) != points_key(points.reshape(-1, 2)[:200])


def test_weighted_entries_of_the_qhull_regular_build_are_not_served(points):
    """Weighted tables cached before geogram triangulated them (Qhull's lifted hull: wrong
    voids on degenerate sets) are under a key no build asks for any more."""
    import hashlib

    from core.cache import CACHE_VERSION

    weights = np.linspace(0.0, 0.01, len(points))
    digest = hashlib.blake2b(digest_size=20)  # the key such an entry was written under
    digest.update(f"alphascoop-table-v{CACHE_VERSION}:{points.shape}".encode())
    digest.update(memoryview(np.ascontiguousarray(points)).cast("B"))
    digest.update(f":weights{weights.shape}".encode())
    digest.update(memoryview(weights).cast("B"))
    assert points_key(points, weights=weights) != digest.hexdigest()
    assert points_key(points, weights=weights) != points_key(points)


def test_prune_keeps_newest(tmp_path):
    import os

    for i in range(5):
        (tmp_path / f"{i}.npz").write_bytes(b"x" * 100)
        os.utime(tmp_path / f"{i}.npz", (i, i))
    prune(tmp_path, max_bytes=250)
    assert sorted(p.name for p in tmp_path.glob("*.npz")) == ["3.npz", "4.npz"]


def test_prune_never_deletes_the_newest_entry(tmp_path):
    import os

    for i in range(3):
        (tmp_path / f"{i}.npz").write_bytes(b"x" * 100)
        os.utime(tmp_path / f"{i}.npz", (i, i))
    prune(tmp_path, max_bytes=50)
    assert [p.name for p in tmp_path.glob("*.npz")] == ["2.npz"]


def test_prune_keeps_the_entry_just_written_even_if_older(tmp_path):
    import os

    for i in range(3):
        (tmp_path / f"{i}.npz").write_bytes(b"x" * 100)
        os.utime(tmp_path / f"{i}.npz", (i, i))
    prune(tmp_path, max_bytes=150, keep=tmp_path / "0.npz")
    assert [p.name for p in tmp_path.glob("*.npz")] == ["0.npz"]


def test_entry_larger_than_the_limit_is_still_cached(cache, points, monkeypatch):
    import core.cache

    monkeypatch.setattr(core.cache, "MAX_CACHE_BYTES", 10)
    other = np.random.default_rng(5).normal(size=(50, 3))
    obtain(other)
    obtain(points)
    assert is_cached(points) and not is_cached(other)


@pytest.mark.parametrize(("value", "limit"), [
    ("8G", 8 * 1024**3), ("500m", 500 * 1024**2), ("3.5GiB", int(3.5 * 1024**3)),
    (" 1024 ", 1024), ("2 TB", 2 * 1024**4), ("", MAX_CACHE_BYTES)])
def test_the_cache_limit_is_a_setting(monkeypatch, value, limit):
    monkeypatch.setenv("ALPHASCOOP_CACHE_LIMIT", value)
    assert cache_limit() == limit


@pytest.mark.parametrize("value", ["lots", "-3G", "8X", "1e9", "G"])
def test_a_cache_limit_that_is_no_size_warns_and_keeps_the_default(monkeypatch, value):
    monkeypatch.setenv("ALPHASCOOP_CACHE_LIMIT", value)
    with pytest.warns(UserWarning, match="ALPHASCOOP_CACHE_LIMIT"):
        assert cache_limit() == MAX_CACHE_BYTES


def test_prune_follows_the_cache_limit_setting(tmp_path, monkeypatch):
    import os

    for i in range(5):
        (tmp_path / f"{i}.npz").write_bytes(b"x" * 100)
        os.utime(tmp_path / f"{i}.npz", (i, i))
    monkeypatch.setenv("ALPHASCOOP_CACHE_LIMIT", "350")
    prune(tmp_path)
    assert sorted(p.name for p in tmp_path.glob("*.npz")) == ["2.npz", "3.npz", "4.npz"]


def test_save_to_missing_folder_is_a_clear_error(tmp_path, points):
    from core.errors import FileFormatError

    ac = AlphaComplex.from_points(points[:30])
    with pytest.raises(FileFormatError, match="does not exist"):
        ac.save(tmp_path / "missing" / "t.npz")


def test_saved_table_gets_normal_permissions(tmp_path, points):
    import os
    import stat

    umask = os.umask(0o022)
    try:
        AlphaComplex.from_points(points[:30]).save(tmp_path / "t.npz")
    finally:
        os.umask(umask)
    assert stat.S_IMODE((tmp_path / "t.npz").stat().st_mode) == 0o644
    assert os.listdir(tmp_path) == ["t.npz"]


@pytest.mark.parametrize("junk", [b"PK\x03\x04 broken zip", b"\x93NUMPY garbage"])
def test_damaged_table_closes_its_file(tmp_path, junk):
    import gc
    import warnings

    from core.errors import FileFormatError

    (tmp_path / "t.npz").write_bytes(junk)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        with pytest.raises(FileFormatError, match=r"t\.npz"):
            AlphaComplex.load(tmp_path / "t.npz")
        gc.collect()
    assert not [w for w in caught if issubclass(w.category, ResourceWarning)]


def test_single_array_is_not_a_table(tmp_path):
    from core.errors import FileFormatError

    np.save(tmp_path / "t.npy", np.zeros(3))
    with pytest.raises(FileFormatError, match=r"not a readable \.npz table"):
        AlphaComplex.load(tmp_path / "t.npy")


def test_signatures_are_cached_with_the_table(cache, points):
    obtain(points)  # an entry without signatures (as `alphascoop export --alpha` leaves it)
    assert not obtain(points).complex.has_signatures
    upgraded = obtain(points, signatures=True)  # computes them and rewrites the entry
    assert upgraded.complex.has_signatures and upgraded.source == "cache"
    reopened = obtain(points, signatures=True).complex
    assert reopened.has_signatures
    upgraded = upgraded.complex
    np.testing.assert_array_equal(reopened.signatures().betti, upgraded.signatures().betti)


def test_a_cache_folder_that_cannot_be_read_is_no_cache(cache, points, monkeypatch):
    from pathlib import Path

    def refused(self):
        raise PermissionError(13, "Permission denied", str(self))

    monkeypatch.setattr(Path, "is_file", refused)
    assert not is_cached(points)
    assert len(obtain(points).complex.points) == 200  # built, not an error

"""A cache entry damaged in any one array, its archive otherwise valid, is refused by its
checksums, removed and rebuilt, the user is told why, and info/export answer as for a good
entry. Entries of the version before checksums still load, checked array by array."""

from __future__ import annotations

import contextlib
import io
import json
import tempfile
import zipfile
from pathlib import Path

import numpy as np
import pytest

from app.cli import main
from core import AlphaComplex
from core.cache import entry_path
from core.errors import FileFormatError
from core.io import read_points
from core.obtain import obtain
from core.storage.compact import unpack

SCAN = Path(__file__).parent / "data" / "corpus" / "pcd" / "pcl_bun01.pcd"


def _entry_arrays() -> list[str]:
    """The arrays a cached entry with its topology holds (a small build, at collection)."""
    ac = AlphaComplex.from_points(np.random.default_rng(0).random((30, 3)))
    ac.signatures()
    with tempfile.TemporaryDirectory() as folder:
        ac.save(Path(folder) / "t.npz")
        with zipfile.ZipFile(Path(folder) / "t.npz") as zf:
            names = [name.removesuffix(".npy") for name in zf.namelist()]
    assert names[-1] == "checksums"  # written last
    return sorted(names[:-1])


ENTRY_ARRAYS = _entry_arrays()


def damaged(array: np.ndarray) -> np.ndarray:
    """The array changed as damage changes one: an index array's rows shifted by one, a
    float column scaled, a flag flipped, a text changed, an empty one given a row; a byte
    flipped when that leaves it as it was (all zeros, one row)."""
    out = np.array(array, copy=True)
    if out.size == 0 and out.ndim >= 1:  # an empty one (no far steps) gains a value
        return np.ones((1, *out.shape[1:]), dtype=out.dtype)
    if out.dtype.kind in "iu" and out.ndim >= 1:
        out = np.roll(out, 1, axis=0)
    elif out.dtype.kind == "f" and out.ndim == 2:
        out[:, -1] *= 1.5
    elif out.dtype.kind == "f":
        out *= 1.5
    elif out.dtype.kind == "b":
        out = ~out
    elif out.dtype.kind == "U":
        out = np.array(str(out) + "x")
    if out.tobytes() == np.asarray(array).tobytes():
        raw = bytearray(out.tobytes())
        raw[len(raw) // 2] ^= 0x01
        out = np.frombuffer(bytes(raw), dtype=out.dtype).reshape(out.shape).copy()
    return out


def rewrite(entry: Path, name: str) -> None:
    """Rewrite the entry (a valid archive, its checksums member kept) with `name` damaged."""
    with np.load(entry, allow_pickle=False) as z:
        arrays = {key: z[key] for key in z.files}
    arrays[name] = damaged(arrays[name])
    assert arrays[name].tobytes() != np.load(entry)[name].tobytes()
    np.savez(entry, **arrays)


@pytest.fixture
def cache(tmp_path, monkeypatch) -> Path:
    folder = tmp_path / "cache"
    monkeypatch.setenv("ALPHASCOOP_CACHE_DIR", str(folder))
    return folder


@pytest.fixture(scope="module")
def scan() -> np.ndarray:
    return read_points(SCAN).points


def test_the_entry_arrays_are_all_listed():
    assert {"points", "enter_values", "enter_steps_3", "simplices_steps_3", "facet_cells",
            "facet_slots", "face_ids_2", "topo_dual_edges_32", "topo_solid_forest_steps",
            "sig_betti_steps", "sig_boundary_runs", "format", "version"} <= set(ENTRY_ARRAYS)


@pytest.mark.parametrize("name", ENTRY_ARRAYS)
def test_damage_of_any_array_is_refused_and_rebuilt(cache, scan, name):
    first = obtain(scan, signatures=True)
    good = first.complex
    rewrite(first.entry, name)
    again = obtain(scan, signatures=True)
    assert again.source == "rebuilt" and again.damage, name
    got = again.complex
    for k in range(4):
        np.testing.assert_array_equal(got.simplices(k), good.simplices(k))
        np.testing.assert_array_equal(got.intervals(k), good.intervals(k))
    np.testing.assert_array_equal(got.signatures().betti, good.signatures().betti)
    assert obtain(scan, signatures=True).source == "cache"  # the rebuilt entry is good


def _run(capsys, *argv: str) -> tuple[int, str, str]:
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


@pytest.fixture(scope="module")
def truth(tmp_path_factory) -> tuple[dict, bytes]:
    """What info --json and export answer from a good build (no cache): the summary and the
    exported file's bytes."""
    folder = tmp_path_factory.mktemp("truth")
    out = io.StringIO()
    with pytest.MonkeyPatch.context() as patch, contextlib.redirect_stdout(out):
        patch.setenv("ALPHASCOOP_CACHE_DIR", str(folder / "cache"))
        assert main(["info", str(SCAN), "--json"]) == 0
        assert main(["export", str(SCAN), "-o", str(folder / "good.ply")]) == 0
    return json.loads(out.getvalue().split("\n}\n")[0] + "}"), (folder / "good.ply").read_bytes()


@pytest.mark.parametrize("name", ENTRY_ARRAYS)
def test_info_and_export_of_a_damaged_entry_are_right(cache, tmp_path, capsys, truth, name):
    run = lambda *argv: _run(capsys, *argv)  # noqa: E731
    truth, good_ply = truth
    assert run("info", str(SCAN), "--json")[0] == 0  # the entry, with its topology
    rewrite(entry_path(read_points(SCAN).points), name)
    code, out, err = run("info", str(SCAN), "--json")
    info = json.loads(out)
    assert code == 0 and info["source"] == "rebuilt" and info["damage"], name
    assert "cached table was damaged" in err and info["damage"] in err
    for key in ("classes", "betti", "volume", "optimal_alpha", "spectrum"):
        assert info[key] == truth[key], key
    rewrite(entry_path(read_points(SCAN).points), name)
    code, _, err = run("export", str(SCAN), "-o", str(tmp_path / "again.ply"))
    assert code == 0 and "cached table was damaged" in err
    assert (tmp_path / "again.ply").read_bytes() == good_ply


def test_a_byte_flipped_in_place_is_refused(cache, scan):
    """A byte changed on disk behind the zip's CRC (the archive not rewritten)."""
    entry = obtain(scan).entry
    with zipfile.ZipFile(entry) as zf:
        info = zf.getinfo("enter_values.npy")
    data = bytearray(entry.read_bytes())
    data[info.header_offset + 30 + len(info.filename) + len(info.extra) + 200] ^= 0x40
    entry.write_bytes(bytes(data))
    again = obtain(scan)
    assert again.source == "rebuilt" and "CRC" in again.damage


def test_the_reason_reaches_the_window_line(cache, scan):
    from app.dataset import Dataset

    entry = obtain(scan).entry
    rewrite(entry, "enter_steps_2")
    again = obtain(scan)
    line = Dataset(path=SCAN, ac=again.complex, spectrum=again.complex.spectrum(),
                   optimal_alpha=None, default_alpha=0.0, signatures=None, n_input=len(scan),
                   report=None, load_seconds=0.0, build_seconds=1.0, source=again.source,
                   damage=again.damage).build_line()
    assert again.damage and f"cached table was damaged: {again.damage})" in line, line


def test_an_entry_without_checksums_keeps_the_array_checks(tmp_path, scan):
    """A table of the version before checksums loads; its arrays are still checked."""
    ac = AlphaComplex.from_points(scan)
    ac.save(tmp_path / "new.npz")
    with np.load(tmp_path / "new.npz", allow_pickle=False) as z:
        arrays = unpack({key: z[key] for key in z.files if key != "checksums"})
    arrays["version"] = np.array(1)
    np.savez(tmp_path / "old.npz", **arrays)
    old = AlphaComplex.load(tmp_path / "old.npz")
    np.testing.assert_array_equal(old.intervals(3), ac.intervals(3))
    arrays["simplices_3"] = arrays["simplices_3"].copy()
    arrays["simplices_3"][0, 0] = len(scan) + 5
    np.savez(tmp_path / "old.npz", **arrays)
    with pytest.raises(FileFormatError, match="simplices_3"):
        AlphaComplex.load(tmp_path / "old.npz")
    arrays = {key: z for key, z in np.load(tmp_path / "new.npz").items() if key != "checksums"}
    np.savez(tmp_path / "stripped.npz", **arrays)  # the current version, its checksums removed
    with pytest.raises(FileFormatError, match="no checksums"):
        AlphaComplex.load(tmp_path / "stripped.npz")


def test_a_checksummed_entry_is_not_checked_again_array_by_array(cache, scan, monkeypatch):
    """The cache trusts what its checksums vouch for (the reopen's cost); a table file
    loaded directly is still checked array by array."""
    from core.storage import tables

    entry = obtain(scan).entry
    calls = []
    real = tables.check_table
    monkeypatch.setattr(tables, "check_table", lambda *a: calls.append(1) or real(*a))
    assert obtain(scan).source == "cache" and calls == []
    AlphaComplex.load(entry)
    assert calls == [1]


def test_a_cached_entry_without_checksums_keeps_the_array_checks(cache, scan):
    """An entry of the version before checksums, broken in one array, is refused through
    the cache too (its arrays are checked), removed and rebuilt."""
    entry = obtain(scan).entry
    with np.load(entry, allow_pickle=False) as z:
        arrays = unpack({key: z[key] for key in z.files if key != "checksums"})
    arrays["version"] = np.array(1)
    arrays["simplices_3"] = arrays["simplices_3"].copy()
    arrays["simplices_3"][0, 0] = len(scan) + 5
    np.savez(entry, **arrays)
    again = obtain(scan)
    assert again.source == "rebuilt" and "simplices_3" in again.damage


ENTRY_CUT_IN_PLACE = """
import sys
import numpy as np
from core.obtain import obtain
points = np.random.default_rng(5).random((3000, 3))
obtain(points)  # builds and stores the entry
again = obtain(points)  # read from the cache
assert again.source == "cache", again.source
again.entry.write_bytes(b"damaged")  # cut in place, not replaced: the same file
ac = again.complex
touched = [float(ac.intervals(k).sum()) for k in range(4)] + [float(ac.points.sum())]
print(len(touched), "arrays read")
"""


def test_an_entry_cut_in_place_leaves_the_complex_read_from_it_whole(tmp_path):
    """A complex read from the cache owns its arrays: cutting its file in place later (not
    something this program does, but a disk tool or a user may) is no bus error."""
    import os
    import subprocess
    import sys

    root = Path(__file__).resolve().parents[1]
    done = subprocess.run([sys.executable, "-c", ENTRY_CUT_IN_PLACE], capture_output=True,
                          text=True, cwd=root, timeout=120,
                          env={**os.environ, "PYTHONPATH": str(root),
                               "ALPHASCOOP_CACHE_DIR": str(tmp_path)})
    assert done.returncode == 0, done.stderr[-1500:]
    assert done.stdout.strip() == "5 arrays read"

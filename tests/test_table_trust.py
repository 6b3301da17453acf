"""Saved and cached tables are checked before use: crafted content (valid zip, wrong values)
is a FileFormatError on load, and the cache rebuilds and replaces such an entry."""

from __future__ import annotations

import io
import zipfile

import numpy as np
import pytest

from core import AlphaComplex
from core.cache import entry_path
from core.errors import FileFormatError
from core.obtain import obtain
from core.storage.compact import unpack
from core.storage.npz import read_npz
from core.storage.tables import FORMAT


@pytest.fixture(params=[2, 3, "weighted"])
def saved(request, tmp_path):
    """(points, the complex with signatures, its full arrays as `save` packs them, input
    weights): version 1, without checksums, so that the array checks alone must find a craft
    (the compact layout's members: tests/test_cache_compact.py)."""
    dim = 3 if request.param == "weighted" else request.param
    rng = np.random.default_rng(dim)
    points = rng.normal(size=(150, dim))
    weights = rng.uniform(0, 0.05, 150) if request.param == "weighted" else None
    ac = AlphaComplex.from_points(points, weights=weights)
    ac.signatures()
    path = tmp_path / "good.npz"
    ac.save(path)
    with np.load(path, allow_pickle=False) as z:
        arrays = unpack({name: z[name].copy() for name in z.files if name != "checksums"})
    arrays["version"] = np.array("1")
    return points, ac, arrays, weights


def top(a: dict) -> int:
    return int(a["dim"])


def swap_first_and_last(arr: np.ndarray) -> np.ndarray:
    out = arr.copy()
    out[[0, -1]] = out[[-1, 0]]
    return out


CRAFTS = {
    # out-of-range indices
    "vertex id": lambda a: a[f"simplices_{top(a)}"].__setitem__((0, -1), len(a["points"])),
    "negative vertex id": lambda a: a["simplices_1"].__setitem__((0, 0), -1),
    "face id": lambda a: a[f"face_ids_{top(a)}"].__setitem__((0, 0), len(a[f"enter_{top(a) - 1}"])),
    "facet cell": lambda a: a["facet_cells"].__setitem__((0, 1), len(a["cell_measure"])),
    "facet without a cell": lambda a: a["facet_cells"].__setitem__((0, 0), -1),
    "input index": lambda a: a["input_index"].__setitem__(0, len(a["points"])),
    "interior order repeats": lambda a: a["facet_interior_order"].__setitem__(1, a[
        "facet_interior_order"][0]),
    "dual edge": lambda a: a["topo_dual_edges"].__setitem__((0, 0), len(a["cell_measure"]) + 1),
    # wrong dtypes
    "float simplices": lambda a: a.update(simplices_1=a["simplices_1"].astype(np.float64)),
    "int64 face ids": lambda a: a.update(face_ids_1=a["face_ids_1"].astype(np.int64)),
    "float32 enter": lambda a: a.update(enter_1=a["enter_1"].astype(np.float32)),
    "float32 points": lambda a: a.update(points=a["points"].astype(np.float32)),
    "int flip": lambda a: a.update(facet_flip=a["facet_flip"].astype(np.int8)),
    "float input index": lambda a: a.update(input_index=a["input_index"].astype(np.float64)),
    "text measure": lambda a: a.update(cell_measure=a["cell_measure"].astype(str)),
    "dim as a pair": lambda a: a.update(dim=np.array([3, 3])),
    "ambient dim as text": lambda a: a.update(ambient_dim=np.array("three")),
    # cell measures
    "doubled cell measures": lambda a: a.update(cell_measure=a["cell_measure"] * 2),
    "cell measures twice over": lambda a: a.update(
        cell_measure=np.concatenate([a["cell_measure"], a["cell_measure"]])),
    "swapped cell measures": lambda a: a.update(cell_measure=swap_first_and_last(
        np.sort(a["cell_measure"]))),
    "negative cell measure": lambda a: a["cell_measure"].__setitem__(0, -1.0),
    # orders and intervals
    "enter not sorted": lambda a: a.update(enter_1=swap_first_and_last(a["enter_1"])),
    "regular below enter": lambda a: a["regular_1"].__setitem__(-1, a["enter_1"][-1] / 2),
    "interior below regular": lambda a: a["interior_1"].__setitem__(-1, a["regular_1"][-1] / 2),
    "NaN regular": lambda a: a["regular_1"].__setitem__(0, np.nan),
    "infinite enter": lambda a: a[f"enter_{top(a)}"].__setitem__(-1, np.inf),
    "interior order unsorted": lambda a: a.update(
        facet_interior_order=a["facet_interior_order"][::-1].copy()),
    "rows not ascending": lambda a: a.update(simplices_1=a["simplices_1"][:, ::-1].copy()),
    "points dropped": lambda a: a.update(points=a["points"][:-1]),
    # lengths that must agree
    "truncated enter": lambda a: a.update(enter_1=a["enter_1"][:-1]),
    "truncated sig_solid": lambda a: a.update(sig_solid=a["sig_solid"][:-1]),
    "truncated sig_measure": lambda a: a.update(sig_measure=a["sig_measure"][:-1]),
    "truncated sig_alphas": lambda a: a.update(sig_alphas=a["sig_alphas"][:-1]),
    "truncated solid forest": lambda a: a.update(topo_solid_forest=a["topo_solid_forest"][:-1]),
    "truncated vertex forest": lambda a: a.update(
        topo_vertex_forest=a["topo_vertex_forest"][:-1]),
    "truncated dual forest": lambda a: a.update(topo_dual_forest=a["topo_dual_forest"][:-1],
                                                topo_dual_edges=a["topo_dual_edges"][:-1]),
    # signatures that disagree with the table (a wrong optimal alpha, a wrong volume)
    "one solid part everywhere": lambda a: a.update(sig_solid=np.ones_like(a["sig_solid"])),
    "betti shifted": lambda a: a.update(sig_betti=a["sig_betti"] + 1),
    "doubled signature measure": lambda a: a.update(sig_measure=a["sig_measure"] * 2),
    "signature alphas scaled": lambda a: a.update(sig_alphas=a["sig_alphas"] / 30),
    "solid forest scaled": lambda a: a.update(topo_solid_forest=a["topo_solid_forest"] / 30),
    "vertex forest scaled": lambda a: a.update(topo_vertex_forest=a["topo_vertex_forest"] / 30),
}


def npy_bytes(header_shape: tuple, array: np.ndarray) -> bytes:
    """An .npy member whose header claims `header_shape` but holds `array`'s bytes."""
    out = io.BytesIO()
    header = {"descr": np.lib.format.dtype_to_descr(array.dtype), "fortran_order": False,
              "shape": header_shape}
    np.lib.format.write_array_header_1_0(out, header)
    out.write(array.tobytes())
    return out.getvalue()


def write_archive(path, arrays: dict, *, lie: dict | None = None) -> None:
    """An .npz of `arrays` with valid zip checksums; members in `lie` get a false header."""
    with zipfile.ZipFile(path, "w") as zf:
        for name, arr in arrays.items():
            arr = np.asarray(arr)
            if lie and name in lie:
                zf.writestr(f"{name}.npy", npy_bytes(lie[name], arr))
            else:
                buf = io.BytesIO()
                np.lib.format.write_array(buf, arr, allow_pickle=False)
                zf.writestr(f"{name}.npy", buf.getvalue())


def crafted(saved, tmp_path, craft: str):
    arrays = saved[2]
    arrays = {name: arr.copy() for name, arr in arrays.items()}
    path = tmp_path / "crafted.npz"
    if craft.startswith("header:"):
        name = craft.split(":")[1]
        write_archive(path, arrays, lie={name: (10**10, *arrays[name].shape[1:])})
    else:
        CRAFTS[craft](arrays)
        write_archive(path, arrays)
    with zipfile.ZipFile(path) as zf:
        assert zf.testzip() is None, "the crafted archive's checksums are valid"
    return path


ALL = [*sorted(CRAFTS), "header:points", "header:enter_1", "header:sig_alphas"]


@pytest.mark.parametrize("craft", ALL)
def test_crafted_table_is_a_file_format_error(saved, tmp_path, craft):
    path = crafted(saved, tmp_path, craft)
    with pytest.raises(FileFormatError) as info:
        AlphaComplex.load(path)
    assert "crafted.npz" in str(info.value) and "\n" not in str(info.value)


@pytest.mark.parametrize("craft", ALL)
def test_cache_rebuilds_and_replaces_a_crafted_entry(saved, tmp_path, monkeypatch, craft):
    points, ac, _, weights = saved
    monkeypatch.setenv("ALPHASCOOP_CACHE_DIR", str(tmp_path / "cache"))
    entry = entry_path(points, weights=weights)
    entry.parent.mkdir()
    crafted(saved, tmp_path, craft).replace(entry)
    obtained = obtain(points, weights=weights, signatures=True)
    assert obtained.source == "rebuilt"
    got = obtained.complex
    assert got.optimal_alpha() == ac.optimal_alpha()
    assert got.shape(ac.optimal_alpha()).measure == ac.shape(ac.optimal_alpha()).measure
    np.testing.assert_array_equal(got.signatures().solid_components,
                                  ac.signatures().solid_components)
    AlphaComplex.load(entry)  # replaced by a good entry


def test_good_tables_pass_the_checks(saved, tmp_path):
    _, ac, arrays, _ = saved
    for compressed in (False, True):
        path = tmp_path / f"ok{compressed}.npz"
        (np.savez_compressed if compressed else np.savez)(path, **arrays)
        loaded = AlphaComplex.load(path)
        assert loaded.optimal_alpha() == ac.optimal_alpha()


def test_a_just_written_table_loads_unchecked_but_keeps_the_archive_checks(saved, tmp_path):
    """verify=False (a table the build process wrote a moment ago) skips the table's array
    checks, giving the same complex, but an archive that lies about its sizes, or a file
    that is not one of our tables, still fails."""
    ac = saved[1]
    path = tmp_path / "own.npz"
    ac.save(path)
    fast = AlphaComplex.load(path, verify=False)
    for k in range(ac.dim + 1):
        np.testing.assert_array_equal(fast.simplices(k), ac.simplices(k))
        np.testing.assert_array_equal(fast.intervals(k), ac.intervals(k))
    crafted(saved, tmp_path, "facet cell")  # a value check: skipped
    AlphaComplex.load(tmp_path / "crafted.npz", verify=False)
    with pytest.raises(FileFormatError, match=r"claims|declares"):
        AlphaComplex.load(crafted(saved, tmp_path, "header:points"), verify=False)
    write_archive(tmp_path / "other.npz", {"x": np.zeros(3)})
    with pytest.raises(FileFormatError, match="format"):
        AlphaComplex.load(tmp_path / "other.npz", verify=False)


@pytest.mark.parametrize("compressed", [False, True])
def test_a_trusted_read_gives_the_same_arrays(tmp_path, compressed):
    """read_npz(trusted=True) reads stored members straight from the file: the same dtypes,
    shapes, memory orders and values as numpy's reader (compressed archives use it)."""
    rng = np.random.default_rng(0)
    arrays = {"points": rng.random((5000, 3)), "rows": rng.integers(0, 9, (700, 4), np.int32),
              "fortran": np.asfortranarray(rng.random((50, 7))), "tag": np.array(FORMAT),
              "empty": np.zeros((0, 3), np.int32), "flags": rng.random(1001) > 0.5,
              "scalar": np.array(3), "big_endian": np.arange(9, dtype=">i8")}
    path = tmp_path / "arrays.npz"
    (np.savez_compressed if compressed else np.savez)(path, **arrays)
    fast, plain = read_npz(path, trusted=True), read_npz(path)
    assert sorted(fast) == sorted(plain) == sorted(arrays)
    for name, want in arrays.items():
        for got in (fast[name], plain[name]):
            assert got.dtype == want.dtype and got.shape == want.shape
            assert got.flags.f_contiguous == want.flags.f_contiguous
            np.testing.assert_array_equal(got, want)


def test_the_trusted_read_really_skips_the_zips_check(tmp_path):
    """A byte of a big stored member changed behind the CRC: numpy's reader refuses it, the
    trusted read returns it, so the fast path is the one taken (it was not dead code)."""
    path = tmp_path / "arrays.npz"
    np.savez(path, ids=np.arange(100_000, dtype=np.int64))
    with zipfile.ZipFile(path) as zf:
        info = zf.getinfo("ids.npy")
    data = bytearray(path.read_bytes())
    names, extra = np.frombuffer(data[info.header_offset + 26:info.header_offset + 30], "<u2")
    last = info.header_offset + 30 + int(names) + int(extra) + info.file_size - 1
    data[last] ^= 0xFF  # the top byte of the last id (little-endian int64)
    path.write_bytes(bytes(data))
    with pytest.raises(FileFormatError, match="CRC"):
        read_npz(path)
    assert read_npz(path, trusted=True)["ids"][-1] != 99_999

"""save/load of the table: exact round trip, read-only arrays, clear errors, atomic writes."""

from __future__ import annotations

import zipfile

import numpy as np
import pytest

from core import AlphaComplex
from core.errors import FileFormatError, InputError
from core.storage.compact import unpack

FILE_ERRORS = (FileFormatError, InputError)


@pytest.fixture(params=[2, 3, "planar"])
def complex_(request):
    """A small complex: 2D, 3D, or 3D input lying in a tilted plane."""
    rng = np.random.default_rng(17)
    if request.param == "planar":
        u, v = rng.integers(0, 2**20, (2, 80)) / 2**20
        return AlphaComplex.from_points(np.column_stack([u, v, 3 * u - v + 2]))
    return AlphaComplex.from_points(rng.random((120, request.param)))


def table_arrays(ac) -> dict:
    """Every array the table hands out, by name."""
    out = {"points": ac.points, "input_index": ac.input_index, "spectrum": ac.spectrum(),
           "cell_measures": ac.cell_measures(), "facet_cells": ac.facet_cells()}
    for k in range(ac.dim + 1):
        out[f"simplices{k}"], out[f"intervals{k}"] = ac.simplices(k), ac.intervals(k)
        if k:
            out[f"face_ids{k}"] = ac.face_ids(k)
    return {name: np.asarray(arr) for name, arr in out.items()}


def test_round_trip_is_exact(complex_, tmp_path) -> None:
    path = tmp_path / "table.npz"
    complex_.save(path)
    loaded = AlphaComplex.load(path)
    assert (loaded.dim, loaded.ambient_dim) == (complex_.dim, complex_.ambient_dim)
    before, after = table_arrays(complex_), table_arrays(loaded)
    for name, arr in before.items():
        assert after[name].dtype == arr.dtype, name
        np.testing.assert_array_equal(after[name], arr, err_msg=name)
        assert not after[name].flags.writeable, f"loaded {name} is writeable"
    spec = np.asarray(complex_.spectrum())
    for alpha in (0.0, float(spec[len(spec) // 2]), float(spec[-1]) * 2):
        for k in range(complex_.dim + 1):
            np.testing.assert_array_equal(loaded.classify(alpha, k), complex_.classify(alpha, k))
        assert loaded.shape(alpha).measure == complex_.shape(alpha).measure
    np.testing.assert_array_equal(loaded.to_ambient(loaded.points),
                                  complex_.to_ambient(complex_.points))


def test_saved_file_is_plain_arrays(complex_, tmp_path) -> None:
    path = tmp_path / "table.npz"
    complex_.save(path)
    with np.load(path, allow_pickle=False) as z:
        for name in z.files:
            assert z[name].dtype != object, f"{name} would need pickle"


def test_save_writes_exactly_the_given_path(tmp_path) -> None:
    ac = AlphaComplex.from_points(np.random.default_rng(0).random((30, 2)))
    path = tmp_path / "my table"
    ac.save(path)
    assert path.is_file(), "save() wrote elsewhere (np.savez appends .npz to bare names)"
    np.testing.assert_array_equal(AlphaComplex.load(path).intervals(1), ac.intervals(1))


def corrupt_random_bytes(path, good: bytes) -> None:
    path.write_bytes(np.random.default_rng(0).bytes(len(good)))


def corrupt_truncated(path, good: bytes) -> None:
    path.write_bytes(good[: len(good) // 2])


def corrupt_empty(path, good: bytes) -> None:
    path.write_bytes(b"")


def corrupt_missing_arrays(path, good: bytes) -> None:
    np.savez(path, points=np.zeros((3, 2)))


def corrupt_pickled_object(path, good: bytes) -> None:
    np.savez(path, points=np.array([{"not": "an array"}], dtype=object))


def corrupt_text_file(path, good: bytes) -> None:
    path.write_text("x y z\n0 0 0\n")


@pytest.mark.parametrize("corrupt", [corrupt_random_bytes, corrupt_truncated, corrupt_empty,
                                     corrupt_missing_arrays, corrupt_pickled_object,
                                     corrupt_text_file])
def test_bad_file_gives_a_clear_error(tmp_path, corrupt) -> None:
    good_path = tmp_path / "good.npz"
    AlphaComplex.from_points(np.random.default_rng(1).random((40, 3))).save(good_path)
    bad = tmp_path / "bad.npz"
    corrupt(bad, good_path.read_bytes())
    with pytest.raises(FILE_ERRORS) as info:
        AlphaComplex.load(bad)
    assert "bad.npz" in str(info.value), "the message should name the file"


@pytest.mark.parametrize("edit", ["index-out-of-range", "nan-interval", "wrong-shape"])
def test_inconsistent_table_is_rejected(tmp_path, edit: str) -> None:
    path = tmp_path / "table.npz"
    AlphaComplex.from_points(np.random.default_rng(2).random((40, 3))).save(path)
    with np.load(path, allow_pickle=False) as z:  # the full arrays, without checksums
        arrays = unpack({name: z[name].copy() for name in z.files if name != "checksums"})
    arrays["version"] = np.array(1)
    ints = sorted((n for n, a in arrays.items() if a.ndim == 2 and a.shape[1] == 4
                   and np.issubdtype(a.dtype, np.integer)), key=lambda n: "simplices" not in n)
    floats = sorted((n for n, a in arrays.items() if n != "points"
                     and np.issubdtype(a.dtype, np.floating)),
                    key=lambda n: ("enter" not in n, -arrays[n].size))
    assert ints and floats, f"cannot find the tetrahedra/intervals among {sorted(arrays)}"
    if edit == "index-out-of-range":
        arrays[ints[0]][0, -1] = 10**6
    elif edit == "nan-interval":
        arrays[floats[0]].flat[0] = np.nan
    else:
        arrays[ints[0]] = arrays[ints[0]][:, :3]
    np.savez(path, **arrays)
    with pytest.raises(FILE_ERRORS):
        AlphaComplex.load(path)


def test_missing_file_gives_a_clear_error(tmp_path) -> None:
    with pytest.raises((*FILE_ERRORS, FileNotFoundError)) as info:
        AlphaComplex.load(tmp_path / "nowhere.npz")
    assert "nowhere.npz" in str(info.value)


def test_failed_write_leaves_the_old_file_intact(tmp_path, monkeypatch) -> None:
    path = tmp_path / "table.npz"
    AlphaComplex.from_points(np.random.default_rng(3).random((30, 3))).save(path)
    before = path.read_bytes()
    real_open = zipfile.ZipFile.open

    def disk_full(self, name, mode="r", *args, **kwargs):
        if mode == "w":
            raise OSError(28, "No space left on device")
        return real_open(self, name, mode, *args, **kwargs)

    monkeypatch.setattr(zipfile.ZipFile, "open", disk_full)
    other = AlphaComplex.from_points(np.random.default_rng(4).random((50, 3)))
    with pytest.raises((*FILE_ERRORS, OSError)):
        other.save(path)
    monkeypatch.undo()
    assert path.read_bytes() == before, "the existing table was damaged by a failed save"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["table.npz"], "temporary file left"


def test_save_into_missing_folder_gives_a_clear_error(tmp_path) -> None:
    ac = AlphaComplex.from_points(np.random.default_rng(5).random((20, 2)))
    with pytest.raises((*FILE_ERRORS, OSError)) as info:
        ac.save(tmp_path / "no" / "such" / "folder" / "t.npz")
    assert "t.npz" in str(info.value) or "folder" in str(info.value)


def test_signatures_computed_before_saving_come_back_without_a_topology_pass(
        complex_, tmp_path, monkeypatch) -> None:
    signatures = complex_.signatures()
    path = tmp_path / "with_signatures.npz"
    complex_.save(path)
    import core.topology.betti

    monkeypatch.setattr(core.topology.betti, "build_topology",
                        lambda ac: pytest.fail("the saved topology was not used"))
    loaded = AlphaComplex.load(path)
    for name in ("alphas", "betti", "solid_components", "measure", "boundary_measure"):
        np.testing.assert_array_equal(getattr(loaded.signatures(), name),
                                      getattr(signatures, name))
    np.testing.assert_array_equal(loaded.spectrum(), complex_.spectrum())
    assert loaded.optimal_alpha() == complex_.optimal_alpha()
    for alpha in complex_.spectrum()[:: max(1, len(complex_.spectrum()) // 25)]:
        assert loaded.betti(alpha) == complex_.betti(alpha)
    for name in ("components", "cavities"):
        np.testing.assert_array_equal(getattr(loaded.persistence(), name),
                                      getattr(complex_.persistence(), name))


@pytest.mark.parametrize("edit", ["short-betti", "unsorted-alphas", "edges-mismatch"])
def test_damaged_signatures_are_rejected(tmp_path, edit: str) -> None:
    path = tmp_path / "table.npz"
    ac = AlphaComplex.from_points(np.random.default_rng(3).random((60, 3)))
    ac.signatures()
    ac.save(path)
    with np.load(path, allow_pickle=False) as z:  # the full arrays, without checksums
        arrays = unpack({name: z[name].copy() for name in z.files if name != "checksums"})
    arrays["version"] = np.array(1)
    if edit == "short-betti":
        arrays["sig_betti"] = arrays["sig_betti"][:-1]
    elif edit == "unsorted-alphas":
        arrays["sig_alphas"] = arrays["sig_alphas"][::-1].copy()
    else:
        arrays["topo_dual_edges"] = arrays["topo_dual_edges"][:-1]
    np.savez(path, **arrays)
    with pytest.raises(FileFormatError, match=r"table\.npz"):
        AlphaComplex.load(path)

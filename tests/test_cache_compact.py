"""Cache entries in the compact layout (format version 3, core.storage.compact): at most 1000
bytes a point on a scan-like set, every array of a table given back bit for bit (the derived
ones equal to what a fresh build holds), a crafted member a FileFormatError (never another
error), and entries of the layout before (version 2, every array stored) still served."""

from __future__ import annotations

import zipfile
from pathlib import Path

import numpy as np
import pytest

from benchmarks.datasets import noisy_torus
from core import AlphaComplex
from core.cache import entry_path
from core.errors import FileFormatError
from core.obtain import obtain
from core.storage import compact
from core.storage import tables as storage
from core.storage.atomic import atomic_write
from core.storage.checksums import write_npz
from core.storage.mapped import map_arrays
from core.storage.npz import read_npz

BYTES_A_POINT = 1000


@pytest.fixture(scope="module")
def torus() -> np.ndarray:
    """A scan-like set: 30,000 points of a noisy torus shell (the benchmarks' set)."""
    return noisy_torus(30_000, seed=3)


@pytest.fixture(scope="module")
def built(torus) -> AlphaComplex:
    ac = AlphaComplex.from_points(torus)
    ac.signatures()
    return ac


def full_arrays(ac: AlphaComplex, folder: Path) -> dict[str, np.ndarray]:
    """Every array of the table as the layout before stored them (save_mapped writes them
    all, one .npy each)."""
    folder.mkdir()
    assert storage.save_mapped(ac, folder)
    return map_arrays(folder)


def test_an_entry_takes_at_most_1000_bytes_a_point(built, torus, tmp_path):
    entry = obtain(torus, signatures=True, cache_dir=tmp_path).entry
    size = entry.stat().st_size
    assert size / len(torus) <= BYTES_A_POINT, f"{size / len(torus):.0f} bytes a point"
    full = sum(a.nbytes for a in full_arrays(built, tmp_path / "full").values())
    assert full / len(torus) > 2 * BYTES_A_POINT  # what every array stored would take


def _tables() -> dict[str, AlphaComplex]:
    """Tables of every kind whose layout differs: 3D, 2D, weighted, two modes."""
    rng = np.random.default_rng(5)
    shell = noisy_torus(3000, seed=4)
    out = {"3D": AlphaComplex.from_points(shell),
           "2D": AlphaComplex.from_points(rng.random((2000, 2))),
           "weighted": AlphaComplex.from_points(rng.normal(size=(1500, 3)),
                                                weights=rng.uniform(0, 0.05, 1500)),
           "density": AlphaComplex.from_points(shell, density=6),
           "anisotropic": AlphaComplex.from_points(shell, anisotropy=0.5)}
    for ac in out.values():
        ac.signatures()
    return out


TABLES = _tables()


@pytest.mark.parametrize("kind", sorted(TABLES))
def test_every_array_comes_back_bit_for_bit(kind, tmp_path):
    ac = TABLES[kind]
    ac.save(tmp_path / "t.npz")
    members = dict(read_npz(tmp_path / "t.npz"))
    assert str(members.pop("checksums").dtype).startswith("<U")
    got, want = compact.unpack(members), full_arrays(ac, tmp_path / "full")
    assert sorted(got) == sorted(want)
    for name, array in want.items():
        assert got[name].dtype == array.dtype and got[name].shape == array.shape, name
        assert got[name].tobytes() == array.tobytes(), name
    loaded = AlphaComplex.load(tmp_path / "t.npz")
    for k in range(ac.dim + 1):
        np.testing.assert_array_equal(loaded.intervals(k), ac.intervals(k))
        np.testing.assert_array_equal(loaded.simplices(k), ac.simplices(k))
        if k:
            np.testing.assert_array_equal(loaded.face_ids(k), ac.face_ids(k))
    for name in ("alphas", "betti", "solid_components", "measure", "boundary_measure"):
        np.testing.assert_array_equal(getattr(loaded.signatures(), name),
                                      getattr(ac.signatures(), name))
    alpha = ac.optimal_alpha()
    assert loaded.optimal_alpha() == alpha and loaded.betti(alpha) == ac.betti(alpha)
    np.testing.assert_array_equal(loaded.shape(alpha).regular_facets,
                                  ac.shape(alpha).regular_facets)


def test_a_classic_entry_is_compact(tmp_path):
    """The classic tables leave their derivable arrays out (a codec that no longer gives
    its arrays back would keep them, silently larger)."""
    TABLES["3D"].save(tmp_path / "t.npz")
    with zipfile.ZipFile(tmp_path / "t.npz") as zf:
        names = {name.removesuffix(".npy") for name in zf.namelist()}
    for left_out in ("regular_1", "interior_2", "enter_2", "face_ids_3", "face_ids_1",
                     "simplices_2", "sig_alphas", "sig_measure", "sig_betti", "facet_flip",
                     "topo_dual_forest", "input_index"):
        assert left_out not in names, left_out


def _crafted(members: dict, name: str) -> dict:
    """The members with `name` changed as a crafted file would change it (its checksums
    then written anew): ints shifted, floats scaled, an empty array given a value."""
    out = dict(members)
    array = np.array(members[name])
    if array.size == 0 and array.ndim:
        out[name] = np.ones((1, *array.shape[1:]), dtype=array.dtype)
    elif array.dtype.kind in "iu" and array.ndim:
        out[name] = np.roll(array, 1, axis=0) + np.ones_like(array)
    elif array.dtype.kind == "f":
        out[name] = array * 1.5 - 1
    elif array.dtype.kind == "b":
        out[name] = ~array
    else:
        out[name] = np.array(str(array) + "x")
    return out


def _members(ac: AlphaComplex, path: Path) -> dict:
    ac.save(path)
    members = dict(read_npz(path))
    members.pop("checksums")
    return members


@pytest.fixture(scope="module")
def members_3d(tmp_path_factory) -> dict:
    return _members(TABLES["3D"], tmp_path_factory.mktemp("m") / "t.npz")


def test_a_crafted_member_is_a_format_error_or_a_table_that_passes(members_3d, tmp_path):
    """Every member changed, its checksums valid: loading raises FileFormatError or gives a
    table (some values, such as a boundary measure, have no other source to be checked
    against), never another error."""
    for name in sorted(members_3d):
        path = tmp_path / f"{name}.npz"
        atomic_write(path, lambda handle, n=name: write_npz(handle, _crafted(members_3d, n)))
        try:
            AlphaComplex.load(path)
        except FileFormatError as error:
            assert path.name in str(error) and "\n" not in str(error), name


def test_an_entry_of_the_layout_before_is_served(built, torus, tmp_path):
    """A version-2 entry (every array stored) is a cache hit, equal to the build."""
    arrays = {**full_arrays(built, tmp_path / "full"), "version": np.array(2)}
    entry = entry_path(torus, folder=tmp_path / "cache")
    entry.parent.mkdir()
    atomic_write(entry, lambda handle: write_npz(handle, arrays))
    got = obtain(torus, signatures=True, cache_dir=tmp_path / "cache")
    assert got.source == "cache" and got.entry == entry
    for k in range(4):
        np.testing.assert_array_equal(got.complex.intervals(k), built.intervals(k))
    np.testing.assert_array_equal(got.complex.signatures().betti, built.signatures().betti)


def _one_by_one(full: dict) -> dict:
    """pack's members the slow way: each codec tried on its own, kept if it unpacks."""
    out = dict(full)
    for packer in compact.PACKERS:
        trial = dict(out)
        packer(full, trial)
        if compact.unpacks_to(trial, full):
            out = trial
    out = compact.without_derived(full, out)
    return out if compact.unpacks_to(out, full) else dict(full)


@pytest.mark.parametrize("kind", sorted(TABLES))
def test_pack_checks_a_usual_table_with_one_unpack(kind, tmp_path, monkeypatch):
    """Every codec at once, checked by one unpack (a classic table); the members are the
    ones codec-by-codec trials give, for every kind of table."""
    full = dict(full_arrays(TABLES[kind], tmp_path / "full"))
    want = _one_by_one(full)
    calls = []
    unpack = compact.unpack
    monkeypatch.setattr(compact, "unpack", lambda m: calls.append(1) or unpack(m))
    got = compact.pack(full)
    assert sorted(got) == sorted(want)
    assert all(got[n].dtype == want[n].dtype and got[n].tobytes() == want[n].tobytes()
               for n in want)
    if kind in ("2D", "3D"):
        assert len(calls) == 1


def test_a_codec_that_does_not_give_back_is_left_out(tmp_path, monkeypatch):
    """One codec losing an array: the others still pack, and the entry unpacks exactly."""
    full = dict(full_arrays(TABLES["3D"], tmp_path / "full"))

    def lossy(a, out):
        out["cell_measure"] = a["cell_measure"].astype(np.float32)

    monkeypatch.setattr(compact, "PACKERS", (*compact.PACKERS[:3], lossy,
                                             *compact.PACKERS[3:]))
    got = compact.pack(full)
    assert got["cell_measure"].dtype == np.float64
    assert "simplices_2" not in got and "facet_flip" not in got  # the other codecs packed
    back = compact.unpack(got)
    assert sorted(back) == sorted(full)
    assert all(back[n].tobytes() == full[n].tobytes() for n in full)

"""A table handed over as mapped .npy files (core.storage.mapped, core.storage.tables.save_mapped):
the same arrays as the saved file unpacked (core.storage.compact), read-only, every query the
same, and the mapping gone with the complex."""

from __future__ import annotations

import gc
from pathlib import Path

import numpy as np
import pytest

from core import AlphaComplex
from core.query.cursor import cursor_orders
from core.storage import mapped
from core.storage import tables as storage
from core.storage.compact import unpack
from core.storage.npz import read_npz


def mapped_regions(folder: Path) -> list[str]:
    """The lines of this process's memory map that map a file of folder."""
    return [line for line in Path("/proc/self/maps").read_text().splitlines()
            if str(folder) in line]


@pytest.fixture(params=[2, 3])
def built(request, tmp_path):
    """A complex with its signatures (dims 2 and 3), saved both ways."""
    points = np.random.default_rng(request.param).random((800, request.param))
    ac = AlphaComplex.from_points(points)
    ac.signatures()
    ac.save(tmp_path / "table.npz")
    (tmp_path / "shared").mkdir()
    assert storage.save_mapped(ac, tmp_path / "shared")
    return ac, tmp_path


def test_a_mapped_table_holds_the_saved_files_arrays_bit_for_bit(built):
    _, folder = built
    archive = read_npz(folder / "table.npz")
    archive.pop("checksums")  # an archive's only: the folder is read just after it is written
    theirs = unpack(archive)  # the file's full arrays (its compact members unpacked)
    mine = mapped.map_arrays(folder / "shared")
    assert sorted(theirs) == sorted(mine) and "sig_betti" in mine
    for name, array in theirs.items():
        assert mine[name].dtype == array.dtype and mine[name].shape == array.shape, name
        assert mine[name].tobytes() == array.tobytes(), name
        assert not mine[name].flags.writeable
    loaded = AlphaComplex.load(folder / "shared", verify=True)  # every check passes too
    assert mapped_regions(folder / "shared") and not loaded.points.flags.writeable


def test_every_query_of_a_mapped_table_is_the_loaded_ones(built):
    """Read-only arrays all the way down: nothing of a complex's queries writes into them."""
    ac, folder = built
    mine = AlphaComplex.load(folder / "shared", verify=False)
    theirs = AlphaComplex.load(folder / "table.npz")
    for alpha in theirs.spectrum()[:: max(1, len(theirs.spectrum()) // 9)]:
        assert mine.betti(alpha) == theirs.betti(alpha)
        np.testing.assert_array_equal(mine.shape(alpha).cells, theirs.shape(alpha).cells)
        np.testing.assert_array_equal(mine.cursor().move(alpha).regular_facets,
                                      theirs.cursor().move(alpha).regular_facets)
    probe = np.random.default_rng(9).random((50, ac.dim))
    np.testing.assert_array_equal(mine.contains(probe, alpha=theirs.optimal_alpha()),
                                  theirs.contains(probe, alpha=theirs.optimal_alpha()))
    fresh = AlphaComplex.load(folder / "shared", verify=True)  # topology computed anew
    fresh_topology = AlphaComplex(fresh.points, fresh.input_index, fresh.index, fresh.frame,
                                  fresh.ambient_dim, fresh.mode, fresh.weights)
    np.testing.assert_array_equal(fresh_topology.signatures().betti, theirs.signatures().betti)
    assert fresh_topology.optimal_alpha() == theirs.optimal_alpha()
    np.testing.assert_array_equal(fresh_topology.persistence().cavities,
                                  theirs.persistence().cavities)
    orders = cursor_orders(mine.index)
    assert mine.cursor(orders).move(theirs.optimal_alpha()).cells.tobytes() == (
        theirs.cursor().move(theirs.optimal_alpha()).cells.tobytes())


def test_a_write_through_a_mapped_array_is_an_error_not_a_change(built):
    _, folder = built
    ac = AlphaComplex.load(folder / "shared", verify=False)
    with pytest.raises(ValueError, match="read-only"):
        ac.points[0, 0] = 5.0


def test_the_mapping_outlives_the_files_and_goes_with_the_complex(built):
    """Unlinked at once (as the window does once both readers mapped them), the pages stay
    readable; dropping the complex returns them (no line of the folder in the memory map)."""
    ac, folder = built
    shared = folder / "shared"
    mine = AlphaComplex.load(shared, verify=False)
    cursor = mine.cursor()
    for path in shared.iterdir():
        path.unlink()
    assert mapped_regions(shared)  # still mapped, though unlinked
    np.testing.assert_array_equal(mine.points, ac.points)
    assert cursor.move(ac.optimal_alpha()).cells.tobytes() == (
        ac.cursor().move(ac.optimal_alpha()).cells.tobytes())
    del mine, cursor
    gc.collect()
    assert mapped_regions(shared) == []


def test_too_little_room_writes_nothing(tmp_path, monkeypatch):
    ac = AlphaComplex.from_points(np.random.default_rng(1).random((300, 3)))
    needed = mapped.bytes_needed({"points": ac.points})
    assert mapped.has_room(tmp_path, needed)
    monkeypatch.setattr(mapped, "ROOM_MARGIN", 2**62)  # a full /dev/shm
    assert not mapped.has_room(tmp_path, needed)
    assert storage.save_mapped(ac, tmp_path) is False
    assert list(tmp_path.iterdir()) == []
    assert not mapped.has_room(tmp_path / "missing", 1)

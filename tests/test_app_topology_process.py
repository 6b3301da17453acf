"""The topology pass in a child process: the same topology as the pass in this
process, handed over before the cache entry is upgraded, Cancel kills it (before and during
that rewrite, which leaves the old entry whole), and nothing is left in the temp dir."""

from __future__ import annotations

import multiprocessing
import os
import shutil
import signal
import subprocess
import sys
import tempfile
import threading
import time
from pathlib import Path

import numpy as np
import pytest
from child_cancel import cancel_at

from app import child_process, topology_process
from app.messages import TopologyJob
from app.topology_child import TopologyChild, start_topology
from app.topology_file import read_topology, write_topology
from core import AlphaComplex
from core.cache import load_cached
from core.errors import Cancelled, FileFormatError
from core.obtain import obtain

ROOT = Path(__file__).resolve().parents[1]


@pytest.fixture(autouse=True)
def private_cache(tmp_path, monkeypatch):
    """Each test starts with an empty table cache."""
    monkeypatch.setenv("ALPHASCOOP_CACHE_DIR", str(tmp_path / "cache"))


def never(*_args) -> None:
    """A progress callback that ignores its reports."""


def my_scratch() -> list[Path]:
    """This process's scratch folders in the temp dir."""
    return list(Path(tempfile.gettempdir()).glob(f"alphascoop-*-{os.getpid()}-*"))


def blobs(n: int, dim: int, seed: int) -> np.ndarray:
    """(n, dim) two noisy blobs and a ring: components, a hole and voids over the spectrum."""
    rng = np.random.default_rng(seed)
    angle = rng.uniform(0, 2 * np.pi, n // 2)
    ring = np.zeros((n // 2, dim))
    ring[:, 0], ring[:, 1] = np.cos(angle), np.sin(angle)
    ring += rng.normal(scale=0.1, size=ring.shape)
    ball = rng.normal(scale=0.3, size=(n - n // 2, dim)) + 3.0
    return np.concatenate([ring, ball])


def assert_same_topology(parts, here: AlphaComplex, same_default: bool = True) -> None:
    """parts (from the child) equal the pass computed here, array for array (the default
    alpha too, with `same_default`)."""
    sig, own = parts.signatures, here.signatures()
    for name in ("alphas", "betti", "solid_components", "measure", "boundary_measure"):
        np.testing.assert_array_equal(getattr(sig, name), getattr(own, name), err_msg=name)
    assert sig.opening_alpha == own.opening_alpha
    for name in ("vertex_forest", "dual_forest", "dual_edges", "solid_forest"):
        np.testing.assert_array_equal(getattr(parts.topology, name),
                                      getattr(here.topology(), name), err_msg=name)
    for k in (0, here.dim - 1):
        np.testing.assert_array_equal(parts.persistence.diagram(k), here.persistence().diagram(k))
    assert parts.optimal_alpha == here.optimal_alpha()
    assert parts.default_alpha == here.default_alpha() or not same_default


@pytest.mark.parametrize("dim", [3, 2])
def test_the_child_computes_the_same_topology_and_upgrades_the_entry(dim):
    points = blobs(3000, dim, seed=dim)
    obtained = obtain(points)  # the window's load: table cached without its topology
    assert obtained.entry is not None and not load_cached(points).has_signatures
    stages: list[str] = []
    child = start_topology(obtained.complex, obtained.entry, threading.Event())
    parts = child.parts(obtained.complex, lambda _f, stage: stages.append(stage))
    assert_same_topology(parts, AlphaComplex.from_points(points))
    assert child.wait(60)  # the rewrite of the entry follows the hand-over
    assert parts.entry_saved and load_cached(points).has_signatures
    assert "topology: signatures" in stages
    assert multiprocessing.active_children() == [] and my_scratch() == []


def test_without_a_cache_entry_the_child_reads_a_temporary_copy():
    points = blobs(1500, 3, seed=7)
    ac = obtain(points, use_cache=False).complex
    child = start_topology(ac, None, threading.Event())
    parts = child.parts(ac, never)
    assert_same_topology(parts, AlphaComplex.from_points(points))
    assert child.wait(60) and not parts.entry_saved and my_scratch() == []


def test_a_cache_entry_gone_meanwhile_is_not_rewritten_from_the_temporary_copy(tmp_path):
    points = blobs(1500, 3, seed=8)
    ac = obtain(points, use_cache=False).complex
    gone = tmp_path / "entry.npz"  # removed (cache cleared) before the topology ran
    child = start_topology(ac, gone, threading.Event())
    parts = child.parts(ac, never)
    assert_same_topology(parts, AlphaComplex.from_points(points))
    assert child.wait(60)
    assert not parts.entry_saved and not gone.exists() and my_scratch() == []


def test_cancel_kills_the_child_while_it_works_and_leaves_nothing():
    """The child says it computes the signatures (about a second of work left at 60k points): alive
    when Cancel is pressed, and gone soon after, killed (SIGKILL), not finished; the cache
    entry it would have rewritten is untouched and no scratch folder is left."""
    points = blobs(60_000, 3, seed=8)
    obtained = obtain(points)  # cached without its topology: the child would rewrite it
    entry, before = obtained.entry, obtained.entry.read_bytes()
    cache_files = sorted(entry.parent.iterdir())
    seen = cancel_at("topology: signatures", lambda progress, cancel: (
        TopologyChild(entry, cancel).parts(obtained.complex, progress)))
    working, outcome = seen.working, seen.outcome
    assert len(working) == 1 and working[0].name == "alphascoop-topology"
    assert seen.alive_at_cancel == [True]
    assert len(outcome) == 1 and isinstance(outcome[0], Cancelled)
    assert working[0].exitcode == -signal.SIGKILL  # killed mid-work: it did not finish
    assert multiprocessing.active_children() == [] and my_scratch() == []
    assert entry.read_bytes() == before and sorted(entry.parent.iterdir()) == cache_files
    assert not load_cached(points).has_signatures


def test_the_child_hands_over_before_it_rewrites_the_entry(tmp_path):
    """The child's body (run here): when it says HANDED_OVER its file is written and the
    cache entry still is the table without signatures; the rewrite comes after."""
    points = blobs(3000, 3, seed=11)
    entry, target = obtain(points).entry, tmp_path / "topology.npz"
    seen: list[tuple[str, bool, bool]] = []

    def progress(_fraction: float, stage: str) -> None:
        seen.append((stage, target.is_file(), load_cached(points).has_signatures))

    topology_process.topology_in_child(TopologyJob(str(entry), str(entry), str(target), None),
                                       progress, lambda _message: None)
    stages = [stage for stage, _, _ in seen]
    handed, saving = stages.index(topology_process.HANDED_OVER), stages.index(
        topology_process.SAVING)
    assert handed < saving and seen[handed][1:] == (True, False)
    assert load_cached(points).has_signatures


def test_killing_the_child_while_it_rewrites_the_entry_leaves_a_whole_entry():
    """Cancel right after the hand-over, while the child rewrites the entry (60k points):
    the topology was handed over, the child is gone and the entry reads back whole, the
    old table or the new one with its signatures (an atomic write), never a broken one."""
    points = blobs(60_000, 3, seed=12)
    obtained, cancel = obtain(points), threading.Event()
    before = obtained.entry.read_bytes()
    child = TopologyChild(obtained.entry, cancel)
    parts = child.parts(obtained.complex, never)
    cancel.set()
    assert child.wait(60) and parts.entry_saved
    assert multiprocessing.active_children() == [] and my_scratch() == []
    cached = load_cached(points)
    assert cached is not None and cached.input_index.shape == obtained.complex.input_index.shape
    assert cached.has_signatures or obtained.entry.read_bytes() == before


def test_a_child_stopped_with_its_load_is_not_taken_over():
    """Until the topology job takes it over, the child stops with its load's cancel (a
    cancelled or superseded open): then it cannot be taken over, and nothing is left."""
    points = blobs(3000, 3, seed=13)
    obtained, load = obtain(points), threading.Event()
    before = obtained.entry.read_bytes()
    child = TopologyChild(obtained.entry, load)
    load.set()
    assert not child.hand_to(threading.Event())
    child.stop()
    assert multiprocessing.active_children() == [] and my_scratch() == []
    assert obtained.entry.read_bytes() == before


def test_a_child_taken_over_no_longer_stops_with_its_load():
    points = blobs(3000, 3, seed=14)
    obtained, load, job = obtain(points), threading.Event(), threading.Event()
    child = TopologyChild(obtained.entry, load)
    assert child.hand_to(job)
    load.set()  # the next open cancels the finished load's request: not this child any more
    parts = child.parts(obtained.complex, never)
    assert_same_topology(parts, AlphaComplex.from_points(points))
    assert child.wait(60) and load_cached(points).has_signatures
    assert multiprocessing.active_children() == [] and my_scratch() == []


def test_a_child_reads_a_cache_entry_or_a_copy_not_both():
    ac = AlphaComplex.from_points(blobs(200, 3, seed=15))
    with pytest.raises(ValueError):
        TopologyChild(None, threading.Event())
    with pytest.raises(ValueError):
        TopologyChild(Path("table.npz"), threading.Event(), copy=ac)


def test_a_scratch_folder_that_cannot_be_made_fails_the_pass_not_hangs(monkeypatch):
    """The follower's folder failing (a full disk) reaches parts() as that error; before,
    parts() waited for ever, even after Cancel."""
    def full(_prefix):
        raise OSError(28, "No space left on device")

    monkeypatch.setattr("app.topology_child.scratch", full)
    ac = AlphaComplex.from_points(blobs(300, 3, seed=16))
    child = TopologyChild(None, threading.Event(), copy=ac)
    with pytest.raises(OSError, match="No space"):
        child.parts(ac, never)
    assert child.wait(10)


def test_a_topology_file_of_another_table_is_refused(tmp_path):
    one = AlphaComplex.from_points(blobs(400, 3, seed=9))
    other = AlphaComplex.from_points(blobs(500, 3, seed=10))
    write_topology(tmp_path / "t.npz", one, entry_saved=False)
    assert read_topology(tmp_path / "t.npz", one).signatures.betti.shape[1] == 3
    with pytest.raises(FileFormatError, match="not this table's topology"):
        read_topology(tmp_path / "t.npz", other)


def damaged_copies(arrays: dict[str, np.ndarray], ac: AlphaComplex):
    """(name, bad array) pairs a topology file of ac must be refused for: forests of the wrong
    length or out of range, and signatures that disagree with the forests or the cells."""
    n_cells = len(ac.intervals(3))
    betti = arrays["sig_betti"].copy()
    betti[-1, 0] += 1  # the last row: the checks sample spread rows, first and last included
    measure = arrays["sig_measure"].copy()
    measure[-1] *= 1.5
    return (("topo_dual_edges", np.full((len(arrays["topo_dual_edges"]), 2), n_cells + 1)),
            ("topo_vertex_forest", np.zeros(len(ac.points))),
            ("topo_dual_forest", np.zeros(len(arrays["topo_dual_forest"]) + 1)),
            ("topo_solid_forest", arrays["topo_solid_forest"][::-1].copy()),
            ("sig_betti", betti), ("sig_measure", measure),
            ("sig_alphas", ac.spectrum()[:-1]))


def test_a_damaged_topology_file_is_refused_with_the_saved_tables_checks(tmp_path):
    ac = AlphaComplex.from_points(blobs(400, 3, seed=9))
    write_topology(tmp_path / "t.npz", ac, entry_saved=False)
    with np.load(tmp_path / "t.npz", allow_pickle=False) as archive:
        arrays = {name: archive[name] for name in archive.files}
    for name, bad in damaged_copies(arrays, ac):
        np.savez(tmp_path / "bad.npz", **{**arrays, name: bad})
        with pytest.raises(FileFormatError, match=f"not this table's topology .*{name}"):
            read_topology(tmp_path / "bad.npz", ac)
    del arrays["pers_cavities"]
    np.savez(tmp_path / "bad.npz", **arrays)
    with pytest.raises(FileFormatError, match=r"topology \(missing 'pers_cavities'"):
        read_topology(tmp_path / "bad.npz", ac)


@pytest.mark.parametrize("dim", [2, 3])
def test_a_topology_file_written_before_sig_alphas_still_loads(dim):
    """tests/data/topology_file: files write_topology wrote at commit ed1dc8b (no
    sig_alphas) for the table that commit built and saved beside them (a build today numbers
    and rounds its simplices otherwise: a topology file only ever meets its own table)."""
    folder = ROOT / "tests" / "data" / "topology_file"
    with np.load(folder / f"topology_{dim}d.npz", allow_pickle=False) as archive:
        assert "sig_alphas" not in archive.files
    here = AlphaComplex.load(folder / f"table_{dim}d.npz")
    parts = read_topology(folder / f"topology_{dim}d.npz",
                          AlphaComplex.load(folder / f"table_{dim}d.npz"))
    # their default alpha is the one-piece rule's (a hand-over file lives only between a
    # window and its own topology process); the opening alpha itself is found again
    assert_same_topology(parts, here, same_default=False)
    assert parts.entry_saved


def own_name(_progress) -> str:
    """A child's work: the command name ps shows for it."""
    return Path("/proc/self/comm").read_text(encoding="utf-8").strip()


def test_a_child_shows_its_name_in_ps():
    name = child_process.run_in_child(own_name, (), never, threading.Event(),
                                      "alphascoop-topology")
    assert name == "alphascoop-topology"[:15]


def test_orphaned_scratch_folders_are_removed_only_when_their_owner_is_dead(tmp_path):
    dead = subprocess.Popen([sys.executable, "-c", "pass"])
    dead.wait()
    orphan = tmp_path / f"alphascoop-build-{dead.pid}-abc"
    mine = tmp_path / f"alphascoop-topology-{os.getpid()}-def"
    unnamed = tmp_path / "alphascoop-build-xyz"
    for folder in (orphan, mine, unnamed):
        folder.mkdir()
        (folder / "points.npy").write_bytes(b"x")
    assert child_process.remove_orphans(tmp_path) == [orphan]
    assert not orphan.exists() and mine.is_dir() and unnamed.is_dir()


def test_a_scratch_folder_whose_owner_holds_its_lock_is_kept(tmp_path, monkeypatch):
    """A living owner whose pid this process cannot see (another pid namespace) keeps its
    folder: it holds the folder's lock; once released the folder is an orphan."""
    monkeypatch.setattr(tempfile, "tempdir", str(tmp_path))
    with child_process.scratch("alphascoop-build-") as folder:
        monkeypatch.setattr(child_process, "_alive", lambda pid: False)
        assert child_process.remove_orphans(tmp_path) == []
        assert Path(folder).is_dir()
        kept = Path(folder).with_name(Path(folder).name + "-copy")
        shutil.copytree(folder, kept)  # same name pattern, lock file present but not held
    assert child_process.remove_orphans(tmp_path) == [kept]


ORPHAN = """
import sys, threading
from app.child_process import run_in_child
from test_app_topology_process import sleep_in_child
run_in_child(sleep_in_child, (sys.argv[1],), lambda *a: None, threading.Event(), "sleeper")
"""


def running(pid: int) -> bool:
    """True while pid is a process that has not ended (a zombie has)."""
    try:
        stat = Path(f"/proc/{pid}/stat").read_text()
    except OSError:
        return False
    return stat.rpartition(")")[2].split()[0] not in ("Z", "X")


def sleep_in_child(pid_file: str, progress) -> str:
    """A child body that writes its pid and sleeps (long enough to outlive its parent)."""
    Path(pid_file).write_text(str(os.getpid()))
    time.sleep(60)
    return "slept"


def test_a_child_ends_when_its_window_is_killed(tmp_path):
    pid_file = tmp_path / "pid"
    env = {**os.environ, "PYTHONPATH": os.pathsep.join([str(ROOT), str(ROOT / "tests")])}
    parent = subprocess.Popen([sys.executable, "-c", ORPHAN, str(pid_file)], env=env)
    try:
        deadline = time.monotonic() + 60
        while not pid_file.exists() or not pid_file.read_text():
            assert time.monotonic() < deadline and parent.poll() is None
            time.sleep(0.05)
        child = int(pid_file.read_text())
    finally:
        parent.kill()
        parent.wait()
    deadline = time.monotonic() + 10
    while running(child) and time.monotonic() < deadline:
        time.sleep(0.1)
    assert not running(child)

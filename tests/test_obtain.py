"""core.obtain: one path to a complex, a pluggable runner, and the source it reports."""

from __future__ import annotations

import numpy as np
import pytest

from core.cache import entry_path
from core.errors import InputError
from core.obtain import BuildRequest, obtain, run_here


@pytest.fixture
def points() -> np.ndarray:
    """(300, 2) random points."""
    return np.random.default_rng(11).random((300, 2))


class CountingRunner:
    """Builds here and remembers the requests it was given."""

    def __init__(self) -> None:
        self.requests: list[BuildRequest] = []

    def __call__(self, request: BuildRequest, progress=None):
        self.requests.append(request)
        return run_here(request, progress)

    def handed_over(self, ac):
        """Nothing found beside (core.obtain.Runner)."""
        return run_here.handed_over(ac)


def test_the_runner_builds_once_then_the_cache_answers(tmp_path, points):
    runner = CountingRunner()
    first = obtain(points, cache_dir=tmp_path, runner=runner, signatures=True)
    again = obtain(points, cache_dir=tmp_path, runner=runner)
    assert (first.source, again.source) == ("built", "cache")
    assert len(runner.requests) == 1
    request = runner.requests[0]
    assert request.save_to == entry_path(points, folder=tmp_path) == first.entry == again.entry
    assert request.signatures and again.complex.has_signatures
    np.testing.assert_array_equal(again.complex.intervals(2), first.complex.intervals(2))


def test_cache_dir_is_the_only_folder_used(tmp_path, monkeypatch, points):
    monkeypatch.setenv("ALPHASCOOP_CACHE_DIR", str(tmp_path / "environment"))
    obtain(points, cache_dir=tmp_path / "given")
    assert entry_path(points, folder=tmp_path / "given").is_file()
    assert not (tmp_path / "environment").exists()


def test_a_damaged_entry_is_reported_as_rebuilt_once(tmp_path, points):
    entry = entry_path(points, folder=tmp_path)
    entry.write_bytes(b"PK\x03\x04 not really a zip")
    sources = [obtain(points, cache_dir=tmp_path).source for _ in range(2)]
    assert sources == ["rebuilt", "cache"]


def test_no_cache_reads_and_writes_nothing(tmp_path, points):
    runner = CountingRunner()
    obtain(points, cache_dir=tmp_path)
    obtained = obtain(points, cache_dir=tmp_path, use_cache=False, runner=runner)
    assert obtained.source == "built" and obtained.entry is None
    assert runner.requests[0].save_to is None


def test_build_progress_names_the_topology_and_the_save(tmp_path, points):
    stages: list[tuple[float, str]] = []
    obtain(points, cache_dir=tmp_path, signatures=True,
           progress=lambda f, s: stages.append((f, s)))
    names = [s for _, s in stages]
    assert "topology" in names and names[-1] == "saving the table"
    fractions = [f for f, _ in stages]
    assert fractions == sorted(fractions) and fractions[-1] < 1.0


@pytest.mark.parametrize("bad", ["not points", [[1.0, "x"]], object()])
def test_bad_points_are_an_input_error(tmp_path, bad):
    with pytest.raises(InputError):
        obtain(bad, cache_dir=tmp_path)

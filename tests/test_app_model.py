"""ExplorerModel and the info text: alpha snapping, clamping, signals only on real change, and
shape facts read from the signatures (no window)."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from app.dataset import Dataset
from app.info_panel import class_counts, data_lines, shape_lines
from app.model import ExplorerModel, snap_index
from app.numbers import quantity
from core import AlphaComplex

finite = st.floats(0.0, 1e6, allow_nan=False)


@given(st.lists(finite, min_size=1, max_size=30, unique=True), finite)
def test_snap_index_is_the_largest_critical_value_at_or_below(values, alpha) -> None:
    """snap_index picks the last spectrum entry <= alpha (the first one if none is)."""
    spectrum = np.sort(np.array([0.0, *values]))
    spectrum = np.unique(spectrum)
    index = snap_index(spectrum, alpha)
    assert spectrum[index] <= alpha
    assert index == len(spectrum) - 1 or spectrum[index + 1] > alpha


@pytest.fixture(scope="module")
def dataset(tmp_path_factory) -> Dataset:
    """A small built 3D dataset."""
    points = np.random.default_rng(4).normal(size=(300, 3))
    ac = AlphaComplex.from_points(points)
    return Dataset(path=tmp_path_factory.mktemp("d") / "p.npy", ac=ac, spectrum=ac.spectrum(),
                   optimal_alpha=ac.optimal_alpha(), default_alpha=ac.default_alpha(),
                   signatures=ac.signatures(), n_input=300,
                   report=None,
                   load_seconds=0.0, build_seconds=0.0)


@pytest.fixture
def model(dataset):
    """A model holding dataset, with a list recording alphaChanged emissions."""
    m = ExplorerModel()
    m.set_dataset(dataset)
    m.changes = []
    m.alphaChanged.connect(lambda: m.changes.append(m.index))
    return m


def test_starts_at_the_opening_alpha(model, dataset) -> None:
    """A new dataset opens at its opening alpha: inside the spectrum, not empty, not the hull,
    never beyond the optimal one, which stays reachable."""
    assert model.alpha == dataset.default_alpha <= dataset.optimal_alpha
    assert 0 < model.index < model.hull_index()
    model.set_index(model.optimal_index())
    assert model.alpha == dataset.optimal_alpha


def test_signals_only_on_real_change(model) -> None:
    """Same index twice: one signal; out-of-range indexes clamp."""
    start = model.index
    model.set_index(start + 1)
    model.set_index(start + 1)
    model.set_index(10**9)
    model.set_index(10**9)
    model.set_index(-5)
    assert model.changes == [start + 1, model.hull_index(), 0]


def test_set_alpha_snaps_and_shape_follows(model, dataset) -> None:
    """A radius between two critical values shows the lower one's shape."""
    spectrum = dataset.spectrum
    model.set_alpha(0.5 * (spectrum[20] + spectrum[21]))
    assert model.index == 20
    expected = dataset.ac.shape(spectrum[20])
    assert np.array_equal(model.shape.cells, expected.cells)


@pytest.mark.parametrize("step", [0, 40, 1500, 3000, -1])
def test_info_counts_match_the_shape(model, dataset, step) -> None:
    """The info panel's counts (from the signatures) equal the shape's own arrays."""
    model.set_index(min(step, len(dataset.spectrum) - 1) if step >= 0 else model.hull_index())
    shape = model.shape
    cells, facets, singular = class_counts(model)
    assert cells == len(shape.cells)
    assert facets == len(shape.regular_facets)
    assert singular == [len(shape.singular(k)) for k in range(dataset.ac.dim)]
    assert shape_lines(model)[-1] == f"volume {quantity(shape.measure, 6)}"


def test_file_name_is_escaped_in_the_info_text(dataset) -> None:
    """A file name with markup characters is shown as text, not parsed as rich text."""
    from dataclasses import replace

    model = ExplorerModel()
    model.set_dataset(replace(dataset, path=dataset.path.with_name("a<b>&c.npy")))
    assert data_lines(model)[0] == "<b>a&lt;b&gt;&amp;c.npy</b>"


def test_projection_of_lonlat_input_is_shown(dataset, tmp_path) -> None:
    """Points read from longitude/latitude say in which projection their metres are."""
    from dataclasses import replace

    from core.io import read_points

    rng = np.random.default_rng(0)
    path = tmp_path / "rome.csv"
    path.write_text("lon,lat\n" + "".join(f"{12.5 + a},{41.9 + b}\n"
                                          for a, b in rng.uniform(-0.2, 0.2, (20, 2))))
    model = ExplorerModel()
    model.set_dataset(replace(dataset, report=read_points(path).report))
    assert "lengths in metres: UTM zone 33N (EPSG:32633)" in data_lines(model)

"""The alpha panel, layer lists and save dialog on their own (no main window, no VTK view)."""

from __future__ import annotations

import numpy as np
import pytest
from PySide6.QtCore import QLocale, QSettings, Qt
from PySide6.QtGui import QValidator

from app.alpha_panel import AlphaPanel, format_alpha
from app.dataset import Dataset
from app.model import ExplorerModel
from app.palette import default_styles
from app.scene import KINDS_2D, KINDS_3D
from core import AlphaComplex


def make_dataset(points: np.ndarray, name: str) -> Dataset:
    """A built dataset of points, named name."""
    from pathlib import Path

    ac = AlphaComplex.from_points(points)
    return Dataset(path=Path(name), ac=ac, spectrum=ac.spectrum(),
                   optimal_alpha=ac.optimal_alpha(), default_alpha=ac.default_alpha(),
                   signatures=ac.signatures(),
                   n_input=len(points), report=None, load_seconds=0.0, build_seconds=0.0)


@pytest.fixture(scope="module")
def datasets() -> tuple[Dataset, Dataset]:
    """Two different small 3D datasets."""
    rng = np.random.default_rng(11)
    return (make_dataset(rng.normal(size=(250, 3)), "a.npy"),
            make_dataset(rng.uniform(size=(180, 3)), "b.npy"))


@pytest.fixture
def german_locale():
    """The system locale writes decimals with ',' (as on a German desktop)."""
    before = QLocale()
    QLocale.setDefault(QLocale(QLocale.Language.German, QLocale.Country.Germany))
    yield
    QLocale.setDefault(before)


@pytest.fixture
def panel(qtbot, datasets, german_locale):
    """An AlphaPanel on a model showing the first dataset."""
    model = ExplorerModel()
    model.set_dataset(datasets[0])
    widget = AlphaPanel(model)
    qtbot.addWidget(widget)
    return widget


def test_radius_field_accepts_its_own_text_in_any_locale(panel, datasets) -> None:
    """Every value the field shows, and values typed with '.', validate as Acceptable."""
    validator = panel.radius.validator()
    spectrum = datasets[0].spectrum
    texts = [format_alpha(a) for a in spectrum[:: max(1, len(spectrum) // 50)]]
    texts += [panel.radius.text(), "0.5", "1.5e-3", "12"]
    for text in texts:
        assert validator.validate(text, 0)[0] == QValidator.State.Acceptable, text


def test_typed_radius_with_a_dot_moves_the_model(panel, qtbot) -> None:
    """Typing '<r>' with a decimal point and Enter snaps the model under a ',' locale."""
    model = panel.model
    target = 0.5 * (model.spectrum[30] + model.spectrum[31])
    panel.radius.selectAll()
    qtbot.keyClicks(panel.radius, f"{target:.10f}")
    qtbot.keyClick(panel.radius, Qt.Key.Key_Return)
    assert model.index == 30


def test_pending_slider_index_never_lands_on_a_new_dataset(panel, qtbot, datasets) -> None:
    """A slider move still queued when the dataset changes is dropped, not applied to it."""
    model = panel.model
    panel.slider.setValue(5)
    model.set_dataset(datasets[1])
    qtbot.wait(20)
    assert model.dataset is datasets[1]
    assert model.index == model.default_index() != 5
    assert panel.slider.value() == panel.travel.position(model.index)


@pytest.mark.parametrize(("dim", "kinds"), [(2, KINDS_2D), (3, KINDS_3D)])
def test_layer_styles_are_exactly_the_drawn_layers(dim, kinds) -> None:
    """Each dimension lists a style for every layer the scene draws, and nothing else."""
    assert set(default_styles(dim)) == set(kinds)


def test_2d_layer_list_has_no_singular_triangles(qtbot) -> None:
    """The Layers dock of a 2D dataset shows no 'Singular triangles' row."""
    from app.layers_panel import LayersPanel

    layers = LayersPanel()
    qtbot.addWidget(layers)
    layers.set_layers(default_styles(2))
    titles = [row.visible.text() for row in layers.rows.values()]
    assert "Singular triangles" not in titles
    assert set(layers.rows) == set(KINDS_2D)


@pytest.mark.parametrize(("typed", "selected", "expected"), [
    ("shape", "STL surface (binary) (*.stl)", "shape.stl"),
    ("shape", "PLY surface (binary, metadata in comments) (*.ply)", "shape.ply"),
    ("shape.obj", "STL surface (binary) (*.stl)", "shape.obj"),
    ("shape", "", "shape.ply"),
])
def test_save_path_takes_the_extension_of_the_chosen_filter(tmp_path, monkeypatch, typed,
                                                             selected, expected) -> None:
    """A name typed without extension gets the selected filter's one (not always the first)."""
    from app import file_actions
    from app.settings import Preferences
    from core.export import SHAPE_FORMATS

    monkeypatch.setattr("app.file_actions.QFileDialog.getSaveFileName",
                        lambda *args, **kwargs: (str(tmp_path / typed), selected))
    prefs = Preferences(QSettings(str(tmp_path / "s.ini"), QSettings.Format.IniFormat))
    path = file_actions.ask_save_path(None, prefs, "Export shape", SHAPE_FORMATS, "x")
    assert path == tmp_path / expected

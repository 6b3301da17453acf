"""A slider step updates only what changed: dock rows whose text is the same are not set (a
set text re-lays out its label and the dock around it)."""

from __future__ import annotations

import pytest
from PySide6.QtWidgets import QLabel, QLineEdit, QPushButton

from app.alpha_panel import AlphaPanel
from app.info_panel import InfoPanel, shape_lines
from app.model import ExplorerModel
from tests.test_app_signatures import make_dataset, ring_and_ball

pytestmark = pytest.mark.gui


@pytest.fixture(scope="module")
def dataset():
    """A 3D ring and ball with its topology."""
    return make_dataset(ring_and_ball())


@pytest.fixture
def texts_set(monkeypatch):
    """Every (widget, new text, old text) given to a label, line edit or button's setText."""
    seen = []
    for cls in (QLabel, QLineEdit, QPushButton):
        original = cls.setText

        def recording(widget, text, original=original):
            seen.append((widget, text, widget.text()))
            original(widget, text)

        monkeypatch.setattr(cls, "setText", recording)
    return seen


def test_info_dock_sets_only_the_rows_that_changed(qtbot, dataset, texts_set) -> None:
    model = ExplorerModel()
    panel = InfoPanel(model)
    qtbot.addWidget(panel)
    model.set_dataset(dataset)
    model.set_index(len(model.spectrum) // 2)
    for _ in range(5):  # steps until one leaves a row unchanged (the counts often stay)
        before = shape_lines(model)
        texts_set.clear()
        model.set_index(model.index + 1)
        after = shape_lines(model)
        if set(before) & set(after):
            break
    changed = [line for old, line in zip(before, after, strict=True) if old != line]
    assert len(changed) < len(after)
    written = [text for widget, text, _ in texts_set if panel.isAncestorOf(widget)]
    assert sorted(written) == sorted(changed)
    assert panel.shape.text() == "<br>".join(after)


def test_alpha_dock_sets_no_text_it_already_shows(qtbot, dataset, texts_set) -> None:
    model = ExplorerModel()
    panel = AlphaPanel(model)
    qtbot.addWidget(panel)
    model.set_dataset(dataset)
    model.set_index(len(model.spectrum) // 2)
    texts_set.clear()
    model.set_index(model.index + 1)
    assert texts_set  # the radius, r² and step rows changed
    assert [(w, new) for w, new, old in texts_set if new == old] == []

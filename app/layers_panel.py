"""Layers dock: per layer a visibility box, a colour swatch and an opacity spin box.

Changes are style only (styleChanged(name, LayerStyle)); they never recompute geometry.
"""

from __future__ import annotations

from dataclasses import replace

from PySide6.QtCore import QSignalBlocker, Signal
from PySide6.QtGui import QColor
from PySide6.QtWidgets import (
    QCheckBox,
    QColorDialog,
    QDoubleSpinBox,
    QGridLayout,
    QPushButton,
    QWidget,
)

from app.palette import LAYER_TITLES, LayerStyle


class LayerRow:
    """The three editors of one layer."""

    def __init__(self, name: str) -> None:
        """Create the editors for layer name."""
        self.visible = QCheckBox(LAYER_TITLES[name])
        self.colour = QPushButton()
        self.colour.setFixedWidth(36)
        self.colour.setToolTip("colour")
        self.opacity = QDoubleSpinBox(decimals=2, minimum=0.0, maximum=1.0, singleStep=0.05)
        self.opacity.setToolTip("opacity")

    def show(self, style: LayerStyle) -> None:
        """Display style without emitting edits."""
        with QSignalBlocker(self.visible), QSignalBlocker(self.opacity):
            self.visible.setChecked(style.visible)
            self.opacity.setValue(style.opacity)
        self.colour.setStyleSheet(f"background-color: {style.colour}; border: 1px solid #888;")


class LayersPanel(QWidget):
    """Editors for the current dataset's layers."""

    styleChanged = Signal(str, object)

    def __init__(self, parent: QWidget | None = None) -> None:
        """Empty until set_layers."""
        super().__init__(parent)
        self.grid = QGridLayout(self)
        self.rows: dict[str, LayerRow] = {}
        self.styles: dict[str, LayerStyle] = {}

    def set_layers(self, styles: dict[str, LayerStyle]) -> None:
        """Show one row per layer, in the order of styles."""
        for row in self.rows.values():
            for widget in (row.visible, row.colour, row.opacity):
                widget.deleteLater()
        self.rows.clear()
        self.styles = dict(styles)
        for line, (name, style) in enumerate(styles.items()):
            row = LayerRow(name)
            row.show(style)
            for column, widget in enumerate((row.visible, row.colour, row.opacity)):
                self.grid.addWidget(widget, line, column)
                widget.show()  # now, not by the layout's queued show: the dock widens once
            row.visible.toggled.connect(lambda on, n=name: self._edit(n, visible=on))
            row.opacity.valueChanged.connect(lambda v, n=name: self._edit(n, opacity=v))
            row.colour.clicked.connect(lambda _=False, n=name: self._pick_colour(n))
            self.rows[name] = row

    def _edit(self, name: str, **change) -> None:
        """Apply one change to a layer's style and announce it."""
        self.styles[name] = replace(self.styles[name], **change)
        self.rows[name].show(self.styles[name])
        self.styleChanged.emit(name, self.styles[name])

    def _pick_colour(self, name: str) -> None:
        """Ask for a colour (QColorDialog) and apply it when accepted."""
        colour = QColorDialog.getColor(QColor(self.styles[name].colour), self, "Layer colour")
        if colour.isValid():
            self._edit(name, colour=colour.name())

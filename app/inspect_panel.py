"""Inspect dock: the simplex clicked in the view, its vertices, class at alpha and intervals.

The class follows the slider; "Show its spoon" asks the view to draw the smallest empty
sphere through the simplex's vertices (the ball that carves it at its enter alpha).
"""

from __future__ import annotations

from PySide6.QtCore import Qt, Signal
from PySide6.QtWidgets import (
    QCheckBox,
    QFormLayout,
    QLabel,
    QPushButton,
    QScrollArea,
    QSizePolicy,
    QVBoxLayout,
    QWidget,
)

from app.inspect import Inspection, alpha_text
from app.model import ExplorerModel
from app.palette import CLASS_COLOURS
from app.pockets_layer import pocket_at, pocket_text

HINT = "Click a point, edge, triangle or cell in the view (without dragging) to inspect it."
POCKETS_PENDING = "being computed (a molecule's pockets come after its first frame)"


class InspectPanel(QWidget):
    """Shows one Inspection; spoonToggled(bool) and cleared() go to the view."""

    spoonToggled = Signal(bool)
    cleared = Signal()

    def __init__(self, model: ExplorerModel, parent: QWidget | None = None) -> None:
        """Empty until show_item."""
        super().__init__(parent)
        self.model = model
        self.item: Inspection | None = None
        self.title = QLabel(HINT)
        self.title.setWordWrap(True)
        self.fields = {name: QLabel() for name in
                       ("vertices", "class", "enter", "regular", "interior", "coordinates",
                        "pocket")}
        for label in self.fields.values():
            label.setTextInteractionFlags(Qt.TextInteractionFlag.TextSelectableByMouse)
            label.setTextFormat(Qt.TextFormat.RichText)
            label.setWordWrap(True)
            label.setSizePolicy(QSizePolicy.Policy.Ignored, QSizePolicy.Policy.Preferred)
        self.spoon = QCheckBox("Show its spoon")
        self.spoon.setToolTip("the smallest empty sphere through its vertices: the ball that "
                              "carves the simplex at its enter alpha")
        self.clear_button = QPushButton("Clear")
        form = QFormLayout()
        for name, label in self.fields.items():
            form.addRow(name, label)
        content = QWidget()
        column = QVBoxLayout(content)
        column.addWidget(self.title)
        column.addLayout(form)
        column.addWidget(self.spoon)
        column.addWidget(self.clear_button)
        column.addStretch(1)
        scroll = QScrollArea()  # a short dock scrolls instead of clipping rows
        scroll.setWidgetResizable(True)
        scroll.setFrameShape(QScrollArea.Shape.NoFrame)
        scroll.setHorizontalScrollBarPolicy(Qt.ScrollBarPolicy.ScrollBarAlwaysOff)
        scroll.setWidget(content)
        QVBoxLayout(self).addWidget(scroll)
        self.spoon.toggled.connect(self.spoonToggled)
        self.clear_button.clicked.connect(self.clear)
        model.alphaChanged.connect(self.refresh)
        model.datasetChanged.connect(self.clear)
        model.datasetReleased.connect(self.clear)
        model.measuresChanged.connect(self._show_pocket)  # a molecule's pockets came later
        self.clear()

    def show_item(self, item: Inspection) -> None:
        """Show item (from a pick)."""
        self.item = item
        self.title.setText(f"<b>{item.kind} {item.row:,}</b> (row of the {item.k}-simplices)")
        self.fields["vertices"].setText(", ".join(f"{v:,}" for v in item.vertices))
        self.fields["coordinates"].setText("<br>".join(
            f"{', '.join(f'{c:.6g}' for c in xyz)}" for xyz in item.coords))
        for column, name in enumerate(("enter", "regular", "interior")):
            self.fields[name].setText(alpha_text(item.intervals[column]))
        self.spoon.setEnabled(item.k > 0 and self.model.dataset.ac.weights is None)
        self.fields["pocket"].setText(self._pocket(item))
        self.clear_button.setEnabled(True)
        self.refresh()

    def _show_pocket(self) -> None:
        """The shown item's pocket field again (its pockets were measured since)."""
        if self.item is not None:
            self.fields["pocket"].setText(self._pocket(self.item))

    def _pocket(self, item: Inspection) -> str:
        """A molecule's pocket the simplex belongs to (a pocket cell or mouth), with its
        residues; '' otherwise (what became of them while a molecule's are not known)."""
        ds = self.model.dataset
        if ds.molecule is None:
            if not ds.is_molecule:
                return ""
            failure = self.model.measures_failure
            return POCKETS_PENDING if failure is None else f"unknown (measures failed: {failure})"
        pocket = pocket_at(ds.molecule.pockets, item.k, item.row)
        return "" if pocket is None else pocket_text(ds.molecule.pockets, pocket,
                                                     ds.atom_labels)

    def refresh(self) -> None:
        """Update the class for the model's current alpha."""
        if self.item is None or self.model.dataset is None:
            return
        name = self.item.class_name(self.model.alpha)
        self.fields["class"].setText(
            f'<span style="color:{CLASS_COLOURS[name]}">■</span> <b>{name}</b> at '
            f"{alpha_text(self.model.alpha)}")

    def clear(self) -> None:
        """Forget the item (a new dataset, Esc or Clear)."""
        had_item = self.item is not None
        self.item = None
        self.title.setText(HINT)
        for label in self.fields.values():
            label.clear()
        self.spoon.setEnabled(False)
        self.clear_button.setEnabled(False)
        if had_item:
            self.cleared.emit()

    def class_text(self) -> str:
        """The class field as plain text (for tests and screen readers)."""
        return self.fields["class"].text()

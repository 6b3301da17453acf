"""A block of text lines, one QLabel a line: a new line of text re-lays out its own row only.

The info dock shows about six lines about the shape at the current alpha; on a slider step
most stay the same (the dataset's lines, often the class counts). One rich-text label for all
of them re-measured and re-laid out the whole block on every step; here a row's text is set
only when it changed.
"""

from __future__ import annotations

from PySide6.QtCore import Qt
from PySide6.QtWidgets import QLabel, QSizePolicy, QVBoxLayout, QWidget

SEPARATOR = "<br>"  # text() joins the rows as the single label did


def row_label() -> QLabel:
    """A selectable rich-text row that wraps and never asks the dock for width."""
    label = QLabel()
    label.setTextFormat(Qt.TextFormat.RichText)
    label.setTextInteractionFlags(Qt.TextInteractionFlag.TextSelectableByMouse)
    label.setWordWrap(True)
    label.setSizePolicy(QSizePolicy.Policy.Ignored, QSizePolicy.Policy.Preferred)
    return label


class RowLabels(QWidget):
    """Lines of rich text, each in its own label; `set_lines` touches changed rows only."""

    def __init__(self, parent: QWidget | None = None) -> None:
        """An empty block."""
        super().__init__(parent)
        self.rows: list[QLabel] = []
        self.lines: list[str] = []
        self.column = QVBoxLayout(self)
        self.column.setContentsMargins(0, 0, 0, 0)
        self.column.setSpacing(0)
        self.setSizePolicy(QSizePolicy.Policy.Ignored, QSizePolicy.Policy.Preferred)

    def set_lines(self, lines: list[str]) -> int:
        """Show lines; returns how many rows had their text set (unchanged rows keep theirs)."""
        while len(self.rows) < len(lines):
            label = row_label()
            self.rows.append(label)
            self.column.addWidget(label)
        changed = 0
        for i, label in enumerate(self.rows):
            text = lines[i] if i < len(lines) else None
            old = self.lines[i] if i < len(self.lines) else None
            if text == old:
                continue
            changed += 1
            if text is None:
                label.clear()
                label.hide()
            else:
                label.setText(text)
                label.show()
        self.lines = list(lines)
        return changed

    def text(self) -> str:
        """The lines shown, joined as one rich text."""
        return SEPARATOR.join(self.lines)

    def clear(self) -> None:
        """Show nothing."""
        self.set_lines([])

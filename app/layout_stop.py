"""A frameless scroll area that keeps a widget's re-layouts to itself (Qt widgets, no logic).

A label's new text re-lays out its parents up to the window (QLayout.activate always asks its
widget's parent to follow), and a re-laid-out dock area makes the window paint, and compose
all of it in software GL, a second time on every slider step. A scroll area takes its
widget's layout requests itself: above it nothing moves.
"""

from __future__ import annotations

from PySide6.QtCore import Qt
from PySide6.QtWidgets import QFrame, QScrollArea, QWidget


def contained(widget: QWidget, scroll_vertically: bool = True) -> QScrollArea:
    """widget in a frameless scroll area that resizes it and is never lower than widget's
    smallest height (so it takes the room widget took; no horizontal bar, a vertical one only
    if scroll_vertically and the room is smaller still)."""
    area = QScrollArea()
    area.setMinimumHeight(widget.minimumSizeHint().height())
    area.setWidgetResizable(True)
    area.setFrameShape(QFrame.Shape.NoFrame)
    area.setHorizontalScrollBarPolicy(Qt.ScrollBarPolicy.ScrollBarAlwaysOff)
    if not scroll_vertically:
        area.setVerticalScrollBarPolicy(Qt.ScrollBarPolicy.ScrollBarAlwaysOff)
    area.setWidget(widget)
    return area

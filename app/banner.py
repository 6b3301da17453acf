"""The banner over the view that says the dataset shown is a subsample of its file."""

from __future__ import annotations

from PySide6.QtWidgets import QLabel, QVBoxLayout, QWidget

BANNER_STYLE = ("QLabel { background: #fff3c4; color: #5a4300; border-bottom: 1px solid "
                "#d9b84a; padding: 6px 10px; font-weight: bold; }")


def subsample_banner_label() -> QLabel:
    """The banner over the view that says a dataset is a subsample (hidden otherwise)."""
    label = QLabel()
    label.setObjectName("subsample_banner")
    label.setWordWrap(True)
    label.setStyleSheet(BANNER_STYLE)
    label.hide()
    return label


def banner_above(banner: QLabel, view: QWidget) -> QWidget:
    """The central widget: the banner, then the view."""
    box = QWidget()
    column = QVBoxLayout(box)
    column.setContentsMargins(0, 0, 0, 0)
    column.setSpacing(0)
    column.addWidget(banner)
    column.addWidget(view, 1)
    return box

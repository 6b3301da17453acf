"""Showing a modal dialog: one function, so tests can stand in for the user."""

from __future__ import annotations

from PySide6.QtWidgets import QDialog


def run_dialog(dialog: QDialog) -> bool:
    """Show the dialog modally; True when the user accepted it."""
    return dialog.exec() == QDialog.DialogCode.Accepted

"""Help: the shortcuts list covers every menu shortcut and the slider keys; the explanation
names the four classes and r vs r² in plain words."""

from __future__ import annotations

from PySide6.QtGui import QAction, QKeySequence

from app.help import EXPLANATION, ShortcutsDialog, shortcut_rows, show_shortcuts


def menu_shortcuts(window) -> set[str]:
    """Every shortcut bound to an action in the window's menus, as text."""
    return {action.shortcut().toString(QKeySequence.SequenceFormat.NativeText)
            for action in window.findChildren(QAction) if not action.shortcut().isEmpty()}


def test_shortcuts_dialog_lists_every_menu_shortcut_and_the_slider_keys(window, qtbot) -> None:
    """The Help menu's shortcuts table holds each menu action's key and the slider's keys."""
    window.menus["shortcuts"].trigger()
    dialog = window.findChild(ShortcutsDialog)
    assert dialog is not None and dialog.isVisible()
    table = dialog.table
    keys = {table.item(row, 0).text() for row in range(table.rowCount())}
    shortcuts = menu_shortcuts(window)
    assert {"Ctrl+1", "Ctrl+H"} <= shortcuts  # optimal alpha, convex hull
    assert shortcuts <= keys
    assert any("PageUp" in key for key in keys) and any("←" in key for key in keys)
    meanings = [table.item(row, 1).text() for row in range(table.rowCount())]
    assert any("Optimal alpha" in text for text in meanings)
    dialog.close()


def test_shortcut_rows_follow_new_actions(window) -> None:
    """An action added later (another feature's menu entry) appears in the list."""
    action = window.menuBar().actions()[0].menu().addAction("Brand new")
    action.setShortcut(QKeySequence("Ctrl+Shift+F9"))
    assert ("Ctrl+Shift+F9", "File → Brand new") in shortcut_rows(window)
    show_shortcuts(window).close()


def test_what_am_i_looking_at_panel(window, qtbot) -> None:
    """F1 (Help → What am I looking at?) shows the dock explaining the classes and r vs r²."""
    assert not window.explain_dock.isVisible()
    assert window.menus["explain"].shortcut() == QKeySequence(QKeySequence.StandardKey.HelpContents)
    window.menus["explain"].trigger()
    qtbot.waitUntil(window.explain_dock.isVisible)
    text = window.explain_dock.widget().toPlainText()
    for word in ("exterior", "singular", "regular", "interior", "r²", "radius", "CGAL"):
        assert word in text
    assert "<b>r</b>" in EXPLANATION and "<b>r²</b>" in EXPLANATION

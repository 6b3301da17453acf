"""Help: the list of keyboard and mouse shortcuts, and a plain-words "what am I looking at".

The shortcut list is read from the window's own actions, so it never goes stale; keys that
belong to widgets (the slider) and the mouse are listed beside them.
"""

from __future__ import annotations

from PySide6.QtCore import Qt
from PySide6.QtGui import QAction, QKeySequence
from PySide6.QtWidgets import (
    QDialog,
    QDialogButtonBox,
    QDockWidget,
    QHeaderView,
    QMainWindow,
    QMenu,
    QTableWidget,
    QTableWidgetItem,
    QTextBrowser,
    QVBoxLayout,
    QWidget,
)

from app.palette import CLASS_COLOURS

WIDGET_KEYS = (
    ("← / →", "alpha: previous / next critical value (slider focused)"),
    ("PageUp / PageDown", "alpha: a bigger step up / down"),
    ("Home / End", "alpha: the smallest / the largest (convex hull)"),
    ("Enter in r", "go to the shape at the radius typed"),
    ("Left drag", "rotate the view (2D: pan)"),
    ("Shift + left drag, middle drag", "pan the view"),
    ("Wheel, right drag", "zoom"),
    ("Click in the view (no drag)", "inspect the point, edge, triangle or cell under the mouse"),
    ("Esc in the view", "clear the inspected simplex"),
    ("Click a signature plot", "go to the alpha under the mouse; ★ / ▼ markers: optimal / "
                               "suggested alphas"),
)


def swatch(name: str) -> str:
    """A coloured square and the class name, as HTML."""
    return f'<span style="color:{CLASS_COLOURS[name]}">■</span> <b>{name}</b>'


EXPLANATION = f"""
<h3>What am I looking at?</h3>
<p>An <b>alpha shape</b> is what is left of space after carving it with a ball (a
"spoon") of radius <b>alpha</b> wherever the ball fits without touching a point. Small alpha
leaves little more than the points; large alpha leaves their convex hull. The program joins
the points into triangles and tetrahedra (the Delaunay triangulation) once, and every alpha
keeps some of them: a simplex (point, edge, triangle or tetrahedron) is kept when a ball of
radius alpha passing through its corners touches no other point.</p>
<p>At the current alpha every simplex is in one of four classes:</p>
<ul>
<li>{swatch("exterior")}: not part of the shape (the spoon carved it away). Not drawn.</li>
<li>{swatch("singular")}: part of the shape, but it bounds nothing: a triangle with no solid
behind it, a dangling edge, a lone point. On thin surface scans much of the surface is
singular triangles.</li>
<li>{swatch("regular")}: on the surface of a solid part: it bounds a kept tetrahedron (in 2D,
a triangle) on one side and empty space on the other. This is the clean surface an export
writes.</li>
<li>{swatch("interior")}: inside the solid, with kept cells on all sides. Hidden unless the
Interior layer is on (or a clipping plane cuts the shape open).</li>
</ul>
<p>Every simplex has three alphas in the table: it <b>enters</b> the shape (becomes
singular), becomes <b>regular</b>, and becomes <b>interior</b> (∞ = never, e.g. on the
convex hull).</p>
<h3>r and r²</h3>
<p><b>r</b> is alpha as a radius, in the data's own units (metres for most scans): the
spoon's radius, and what the slider, the plots and the command line use. <b>r²</b> is its
square, the value CGAL and gudhi print (gudhi's "filtration value"). Both describe the same
shape: r = 0.01 is r² = 0.0001.</p>
<h3>The signature plots</h3>
<p>Betti numbers count components (b0), tunnels in 3D or holes in 2D (b1) and enclosed voids
(b2) at each alpha; volume and surface area follow. The persistence diagram shows when each
component, hole or void appears (birth) and disappears (death): points far above the
diagonal are real features, points near it are noise.</p>
"""


def action_rows(window: QMainWindow) -> list[tuple[str, str]]:
    """(shortcut, menu path) of every menu action of window that has a shortcut."""
    rows = []
    for menu in window.menuBar().findChildren(QMenu):
        for action in menu.actions():
            keys = action.shortcut()
            if not keys.isEmpty() and not action.isSeparator():
                title = f"{menu.title()} → {action.text()}".replace("&", "")
                rows.append((keys.toString(QKeySequence.SequenceFormat.NativeText), title))
    return list(dict.fromkeys(rows))


def shortcut_rows(window: QMainWindow) -> list[tuple[str, str]]:
    """Every shortcut the user has: the menu actions', then the widgets' and the mouse's."""
    return [*action_rows(window), *WIDGET_KEYS]


class ShortcutsDialog(QDialog):
    """A two-column table: key or mouse gesture, what it does."""

    def __init__(self, rows: list[tuple[str, str]], parent: QWidget | None = None) -> None:
        """Show rows (key, meaning)."""
        super().__init__(parent)
        self.setWindowTitle("Keyboard and mouse shortcuts")
        self.table = QTableWidget(len(rows), 2)
        self.table.setHorizontalHeaderLabels(["Key / mouse", "Does"])
        self.table.verticalHeader().hide()
        self.table.setEditTriggers(QTableWidget.EditTrigger.NoEditTriggers)
        for line, (key, meaning) in enumerate(rows):
            self.table.setItem(line, 0, QTableWidgetItem(key))
            self.table.setItem(line, 1, QTableWidgetItem(meaning))
        header = self.table.horizontalHeader()
        header.setSectionResizeMode(0, QHeaderView.ResizeMode.ResizeToContents)
        header.setStretchLastSection(True)
        buttons = QDialogButtonBox(QDialogButtonBox.StandardButton.Close)
        buttons.rejected.connect(self.reject)
        column = QVBoxLayout(self)
        column.addWidget(self.table)
        column.addWidget(buttons)
        self.resize(620, 420)


class ExplainPanel(QTextBrowser):
    """The "what am I looking at" text: classes and r vs r² in plain words."""

    def __init__(self, parent: QWidget | None = None) -> None:
        """Fill with the explanation."""
        super().__init__(parent)
        self.setHtml(EXPLANATION)
        self.setOpenExternalLinks(False)


def add_help_actions(window: QMainWindow, menu: QMenu,
                     explain_dock: QDockWidget) -> dict[str, QAction]:
    """Help → Shortcuts (Ctrl+/), listing window's menu shortcuts, and Help → What am I
    looking at? (F1), showing explain_dock."""
    shortcuts = menu.addAction("&Keyboard and mouse shortcuts")
    shortcuts.setShortcut(QKeySequence("Ctrl+/"))
    shortcuts.triggered.connect(lambda _=False: show_shortcuts(window))
    looking = menu.addAction("&What am I looking at?")
    looking.setShortcut(QKeySequence(QKeySequence.StandardKey.HelpContents))
    looking.triggered.connect(lambda _=False: show_explanation(explain_dock))
    return {"shortcuts": shortcuts, "explain": looking}


def show_shortcuts(window: QMainWindow) -> ShortcutsDialog:
    """Open the shortcuts dialog (non-modal) and return it."""
    dialog = ShortcutsDialog(shortcut_rows(window), window)
    dialog.setAttribute(Qt.WidgetAttribute.WA_DeleteOnClose)
    dialog.show()
    return dialog


def show_explanation(dock: QDockWidget) -> None:
    """Show and raise the "What am I looking at?" dock."""
    dock.show()
    dock.raise_()

"""File dialogs and the writers behind the File menu: open, export shape/table, screenshot.

Each writer returns the line that says what it wrote; app.menus runs it and shows that line.
"""

from __future__ import annotations

import re
from pathlib import Path

from PySide6.QtWidgets import QFileDialog, QWidget

from app.jobs import Progress
from app.scene import Scene
from app.settings import Preferences
from core import AlphaComplex
from core.complex import at_value
from core.export import write_shape, write_table
from core.geometry.georef import Georef
from core.io import READ_FORMATS


def name_filters(formats: dict[str, str], everything: str | None = None) -> str:
    """Qt file-dialog filter string: optional 'all' entry, then one entry per extension."""
    entries = [f"{desc} (*{ext})" for ext, desc in formats.items()]
    if everything:
        patterns = " ".join(f"*{ext}" for ext in formats)
        entries.insert(0, f"{everything} ({patterns})")
    return ";;".join(entries)


def ask_open_path(parent: QWidget, prefs: Preferences) -> str | None:
    """Ask for a point file to open (every format the core reads); None if cancelled."""
    path, _ = QFileDialog.getOpenFileName(
        parent, "Open point set", prefs.last_dir(),
        name_filters(READ_FORMATS, "All point files") + ";;Any file (*)",
    )
    return path or None


def filter_extension(selected: str, formats: dict[str, str]) -> str:
    """Extension of a dialog filter like 'PLY surface (*.ply)'; the first format's if none."""
    match = re.search(r"\(\*(\.[^)\s]+)\)\s*$", selected or "")
    ext = match.group(1).lower() if match else ""
    return ext if ext in formats else next(iter(formats))


def ask_save_path(parent: QWidget, prefs: Preferences, title: str, formats: dict[str, str],
                  default_name: str) -> Path | None:
    """Ask where to write; adds the chosen filter's extension when none of formats was typed."""
    start = str(Path(prefs.last_dir() or ".") / default_name)
    path, selected = QFileDialog.getSaveFileName(parent, title, start, name_filters(formats))
    if not path:
        return None
    path = Path(path)
    if path.suffix.lower() not in formats:
        path = path.with_name(path.name + filter_extension(selected, formats))
    prefs.set_last_dir(path)
    return path


def write_shape_file(ac: AlphaComplex, alpha: float, path: Path,
                     progress: Progress | None = None, source: Path | None = None,
                     georef: Georef | None = None, manifold: bool = True) -> str:
    """Write the shape at alpha to path with core.export (never over `source`, the points'
    file; back in longitude/latitude when the points were read from them: `georef`; 3D
    surfaces split to a 2-manifold unless `manifold` is False); returns what was written.
    `alpha` is the table's value (a signed radius for weighted points: written as its signed
    square, alpha2)."""
    at = at_value(alpha)
    return write_shape(ac, at.get("alpha"), path, alpha2=at.get("alpha2"), progress=progress,
                       source=source, georef=georef, manifold=manifold).line()


def write_table_file(ac: AlphaComplex, path: Path, progress: Progress | None = None,
                     source: Path | None = None) -> str:
    """Write the interval table to path with core.export (never over `source`); returns what
    was written."""
    return write_table(ac, path, progress=progress, source=source).line()


def write_screenshot(scene: Scene, path: Path) -> str:
    """Save the scene's view as a PNG image, atomically; returns what was written."""
    scene.save_png(path)
    return f"Wrote {path} ({path.stat().st_size:,} bytes)"

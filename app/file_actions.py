"""File dialogs and writers behind the File menu: open, export shape/table, save screenshot."""

from __future__ import annotations

import os
import tempfile
from pathlib import Path

from PySide6.QtWidgets import QFileDialog, QWidget

from app.loading import read_formats
from app.settings import Preferences


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
        name_filters(read_formats(), "All point files") + ";;Any file (*)",
    )
    return path or None


def shape_formats() -> dict[str, str]:
    """Extensions the shape exporter writes (empty when core.export is not available)."""
    try:
        from core.export import SHAPE_FORMATS
    except ImportError:
        return {}
    return dict(SHAPE_FORMATS)


def ask_save_path(parent: QWidget, prefs: Preferences, title: str, formats: dict[str, str],
                  default_name: str) -> Path | None:
    """Ask where to write; adds the first format's extension when none was typed."""
    start = str(Path(prefs.last_dir() or ".") / default_name)
    path, _ = QFileDialog.getSaveFileName(parent, title, start, name_filters(formats))
    if not path:
        return None
    path = Path(path)
    if path.suffix.lower() not in formats:
        path = path.with_name(path.name + next(iter(formats)))
    prefs.set_last_dir(path)
    return path


def export_shape(ac, alpha: float, path: Path) -> str:
    """Write the shape at alpha to path with core.export; returns what was written."""
    from core.export import write_shape

    result = write_shape(ac, alpha, path)
    return describe_written(path, result)


def export_table(ac, path: Path) -> str:
    """Write the interval table to path with core.export; returns what was written."""
    from core.export import write_table

    result = write_table(ac, path)
    return describe_written(path, result)


def table_formats() -> dict[str, str]:
    """Extensions the table exporter writes."""
    try:
        from core.export import TABLE_FORMATS
    except ImportError:
        return {".npz": "interval table, NumPy archive"}
    return dict(TABLE_FORMATS)


def describe_written(path: Path, result: object) -> str:
    """One line for the user: the writer's own summary, else the file and its size."""
    if hasattr(result, "line"):
        return result.line()
    size = path.stat().st_size if path.exists() else 0
    return f"Wrote {path} ({size:,} bytes)"


def save_screenshot(plotter, path: Path) -> str:
    """Save the view as an image, atomically (temp file in the target folder + os.replace)."""
    fd, tmp = tempfile.mkstemp(dir=path.parent, suffix=path.suffix or ".png")
    os.close(fd)
    try:
        plotter.screenshot(tmp)
        os.chmod(tmp, 0o644)
        os.replace(tmp, path)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise
    return describe_written(path, None)

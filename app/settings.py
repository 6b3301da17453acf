"""Preferences kept between runs (QSettings): last directory, recent files, import choices
per file type, the export's manifold box, layer styles."""

from __future__ import annotations

from pathlib import Path

from PySide6.QtCore import QSettings

from app.palette import LayerStyle, default_styles

MAX_RECENT = 8


class Preferences:
    """Typed access to a QSettings store (tests pass an ini file of their own)."""

    def __init__(self, settings: QSettings | None = None) -> None:
        """Use settings, or the user's store for organization 'alphascoop'."""
        self.store = settings or QSettings("alphascoop", "Alpha Scoop")

    def last_dir(self) -> str:
        """Directory of the last file opened or written ('' if none)."""
        return str(self.store.value("last_dir", "", type=str))

    def set_last_dir(self, path: str | Path) -> None:
        """Remember the directory containing path."""
        self.store.setValue("last_dir", str(Path(path).resolve().parent))

    def recent_files(self) -> list[str]:
        """Recently opened files, newest first (only those that still exist)."""
        files = self.store.value("recent_files", [], type=list) or []
        return [f for f in files if Path(f).is_file()]

    def add_recent(self, path: str | Path) -> None:
        """Put path first in the recent files."""
        path = str(Path(path).resolve())
        files = [path, *(f for f in self.recent_files() if f != path)]
        self.store.setValue("recent_files", files[:MAX_RECENT])

    def import_options(self, ext: str) -> tuple[str, int, str]:
        """(columns, subsample count (0 = all points), method) last chosen for files of `ext`
        ('.csv', '.las'...): the import dialog's defaults."""
        key = f"import/{ext.lower().lstrip('.')}"
        return (str(self.store.value(f"{key}/columns", "", type=str)),
                int(self.store.value(f"{key}/subsample", 0, type=int)),
                str(self.store.value(f"{key}/method", "voxel", type=str)))

    def set_import_options(self, ext: str, columns: str, subsample: int, method: str) -> None:
        """Remember the import dialog's choices for files of `ext`."""
        key = f"import/{ext.lower().lstrip('.')}"
        self.store.setValue(f"{key}/columns", columns)
        self.store.setValue(f"{key}/subsample", int(subsample))
        self.store.setValue(f"{key}/method", method)

    def export_manifold(self) -> bool:
        """Whether Export shape splits surfaces to a 2-manifold (default True)."""
        return bool(self.store.value("export/manifold", True, type=bool))

    def set_export_manifold(self, manifold: bool) -> None:
        """Remember the Export shape dialog's manifold choice."""
        self.store.setValue("export/manifold", bool(manifold))

    def styles(self, dim: int, weighted: bool = False) -> dict[str, LayerStyle]:
        """Layer styles for a dim-D dataset (weighted: with the balls layer): defaults
        overridden by saved ones."""
        styles = default_styles(dim, weighted)
        for name, default in styles.items():
            key = f"layers/{dim}d/{name}"
            styles[name] = LayerStyle(
                visible=self.store.value(f"{key}/visible", default.visible, type=bool),
                colour=str(self.store.value(f"{key}/colour", default.colour, type=str)),
                opacity=float(self.store.value(f"{key}/opacity", default.opacity, type=float)),
            )
        return styles

    def set_style(self, dim: int, name: str, style: LayerStyle) -> None:
        """Save one layer's style for dim-D datasets."""
        key = f"layers/{dim}d/{name}"
        self.store.setValue(f"{key}/visible", style.visible)
        self.store.setValue(f"{key}/colour", style.colour)
        self.store.setValue(f"{key}/opacity", style.opacity)

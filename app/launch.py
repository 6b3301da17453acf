"""Start the Qt application and the main window (interactive mode)."""

from __future__ import annotations

import argparse
import gc
import os
import sys

os.environ["QT_API"] = "pyside6"

from PySide6.QtCore import QEvent
from PySide6.QtWidgets import QApplication

from app.dataset import ImportOptions
from app.none_guard import keep_none_alive
from app.resources import SAMPLE_PATH


def options_from_args(args: argparse.Namespace) -> ImportOptions:
    """How the command line asks the file to be read (--columns, --subsample)."""
    return ImportOptions(columns=args.columns, subsample=args.subsample)


def run_window(args: argparse.Namespace) -> int:
    """Open the window on args.file (or the bundled sample) and run the event loop."""
    from app.main_window import MainWindow

    keep_none_alive()  # before any Qt call: see app/none_guard.py
    app = QApplication.instance() or QApplication(sys.argv[:1])
    app.setApplicationName("Alpha Scoop")
    app.setOrganizationName("alphascoop")
    window = MainWindow()
    if args.size:
        window.resize(*args.size)
    elif not window.prefs.store.contains("window/geometry"):
        window.resize(1280, 800)
    if args.alpha is not None:
        window.start_alpha = args.alpha
    if getattr(args, "mode", None) is not None:
        window.set_mode(args.mode, rebuild=False)
    window.start_optimal = bool(args.optimal)
    window.show()
    window.open_path(args.file or SAMPLE_PATH, options_from_args(args))
    code = app.exec()
    close_window(window)
    return code


def close_window(window) -> None:
    """Release the window, its plotters and their VTK objects now, while the interpreter
    and the QApplication are whole, not in whatever order the interpreter's finalization
    would release them."""
    window.close()  # closeEvent stops the workers and closes the scene's plotter
    window.deleteLater()
    QApplication.sendPostedEvents(None, QEvent.Type.DeferredDelete)
    del window
    gc.collect()

"""The window's scene: a Qt render widget (pyvistaqt.QtInteractor) owned by a Scene.

Kept apart from app.scene.view so the off-screen screenshot never imports Qt.
"""

from __future__ import annotations

import os

os.environ["QT_API"] = "pyside6"

from PySide6.QtCore import QTimer
from PySide6.QtWidgets import QWidget
from pyvistaqt import QtInteractor

from app.scene.view import Scene


def interactive_scene(parent: QWidget) -> tuple[Scene, QWidget]:
    """A scene drawing into a new Qt render widget of parent, and that widget (to place in
    a layout). It renders only when asked (auto_update=False), smooths edges with FXAA,
    takes no drops (the window does) and finds the balls a new view shows after its frame."""
    plotter = QtInteractor(parent, auto_update=False)
    plotter.setAcceptDrops(False)
    # FXAA, not multisampling: a software renderer draws a multisampled frame 2-3 times slower
    plotter.render_window.SetMultiSamples(0)
    plotter.renderer.SetUseFXAA(True)
    return Scene(plotter, render=plotter.update,
                 defer=lambda task: QTimer.singleShot(0, task)), plotter

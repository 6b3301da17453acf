"""A slider step as the user feels it, in the real MainWindow: key press -> every event it
caused handled and painted, split into its parts, beside a bare render of the same frame.

`PartTimer` wraps the window's per-step methods at class level (before the window is made:
signals hold the bound methods) and the render window's Start/End events; `Stepper` presses
keys, buttons and markers and drains the event queue; `drag` moves the slider as a mouse drag
does. Nothing here is timed against a bound: the figures are ratios made by the caller.
"""

from __future__ import annotations

import statistics
import time
from collections import defaultdict
from collections.abc import Callable

#: (class path, method) -> part of a step. The scene's methods are timed with the cursor
#: query they trigger subtracted (model.shape is lazy: set_shape asks for it).
PARTS = {
    ("core.query.cursor", "ShapeCursor", "move"): "cursor",
    ("app.scene.view", "Scene", "set_shape"): "scene arrays",
    ("app.scene.view", "Scene", "set_cells"): "scene arrays",
    ("app.colour_view", "Colourer", "update"): "scene arrays",
    ("app.model", "ExplorerModel", "cavities"): "scene arrays",
    ("app.signatures_dock", "SignaturesPanel", "move_cursor"): "plots",
    ("matplotlib.backends.backend_qtagg", "FigureCanvasQTAgg", "paintEvent"): "plots",
    ("app.info_panel", "InfoPanel", "show_shape"): "docks",
    ("app.alpha_panel", "AlphaPanel", "sync"): "docks",
    ("app.inspect_panel", "InspectPanel", "refresh"): "docks",
    ("app.main_window", "MainWindow", "_show_status"): "docks",
}
KINDS = ("arrow", "page", "typed", "optimal", "marker", "back_forward")
DRAIN_ROUNDS = 3  # empty passes of the event queue in a row: nothing more is coming


class PartTimer:
    """Seconds spent in each part since `reset`, nested calls counted once (innermost wins:
    a part's time excludes the parts called inside it)."""

    def __init__(self) -> None:
        self.seconds: dict[str, float] = defaultdict(float)
        self.renders = 0
        self._stack: list[list] = []  # [part, start, child seconds]
        self._render_start = 0.0

    def reset(self) -> None:
        """Start a new step."""
        self.seconds = defaultdict(float)
        self.renders = 0

    def install(self) -> None:
        """Wrap every method of PARTS (call before the window is made)."""
        import importlib

        for (module, cls, name), part in PARTS.items():
            owner = getattr(importlib.import_module(module), cls)
            setattr(owner, name, self._wrap(getattr(owner, name), part))

    def _wrap(self, method: Callable, part: str) -> Callable:
        timer = self

        def wrapped(*args, **kwargs):
            timer._stack.append([part, time.perf_counter(), 0.0])
            try:
                return method(*args, **kwargs)
            finally:
                part_, start, children = timer._stack.pop()
                spent = time.perf_counter() - start
                timer.seconds[part_] += spent - children
                if timer._stack:
                    timer._stack[-1][2] += spent

        wrapped.__name__ = method.__name__
        wrapped.__doc__ = method.__doc__
        return wrapped

    def watch_renders(self, render_window) -> None:
        """Time every VTK render of render_window (upload and draw) as the part "render"."""
        def started(*_):
            self._render_start = time.perf_counter()

        def ended(*_):
            spent = time.perf_counter() - self._render_start
            self.seconds["render"] += spent
            self.renders += 1
            if self._stack:  # a render inside a timed method is not that method's time
                self._stack[-1][2] += spent

        render_window.AddObserver("StartEvent", started)
        render_window.AddObserver("EndEvent", ended)


def drain() -> None:
    """Handle every queued event (posted events, the zero timers, paints) until the queue
    stays empty DRAIN_ROUNDS passes in a row."""
    from PySide6.QtCore import QCoreApplication, QEventLoop

    quiet = 0
    while quiet < DRAIN_ROUNDS:
        QCoreApplication.sendPostedEvents()
        busy = QCoreApplication.processEvents(QEventLoop.ProcessEventsFlag.AllEvents)
        quiet = 0 if busy else quiet + 1


class Stepper:
    """Steps of each kind in a shown window holding a dataset with its topology."""

    def __init__(self, win) -> None:
        self.win = win
        self.model = win.model
        self.slider = win.alpha_panel.slider
        self.flip = False

    def press(self, kind: str) -> None:
        """One user action of `kind` (arrows and pages alternate direction; typed alpha and
        Optimal alternate with each other's targets; a marker click alternates markers)."""
        from PySide6.QtCore import Qt
        from PySide6.QtTest import QTest

        self.flip = not self.flip
        if kind == "arrow":
            QTest.keyClick(self.slider, Qt.Key.Key_Right if self.flip else Qt.Key.Key_Left)
        elif kind == "page":
            QTest.keyClick(self.slider, Qt.Key.Key_PageUp if self.flip else Qt.Key.Key_PageDown)
        elif kind == "typed":
            self.type_alpha(self.typed_target())
        elif kind == "optimal":
            if self.flip:
                QTest.mouseClick(self.win.alpha_panel.optimal, Qt.MouseButton.LeftButton)
            else:
                self.type_alpha(self.typed_target())
        elif kind == "marker":
            self.click_marker()
        elif kind == "back_forward":
            QTest.keyClick(self.slider, Qt.Key.Key_Left if not self.flip else Qt.Key.Key_Right,
                           Qt.KeyboardModifier.AltModifier)
        else:
            raise ValueError(f"unknown step kind {kind!r}")

    def typed_target(self) -> float:
        """An alpha to type: alternately a quarter and a half of the optimal alpha's index."""
        spectrum = self.model.spectrum
        index = self.model.optimal_index()
        return float(spectrum[max(1, index // (4 if self.flip else 2))])

    def type_alpha(self, alpha: float) -> None:
        """Type alpha into the radius field and press Enter, as a user does."""
        from PySide6.QtCore import Qt
        from PySide6.QtTest import QTest

        field = self.win.alpha_panel.radius
        field.setFocus()
        field.selectAll()
        QTest.keyClicks(field, f"{alpha:.9g}")
        QTest.keyClick(field, Qt.Key.Key_Return)
        self.slider.setFocus()

    def click_marker(self) -> None:
        """Click the optimal (★) or a suggested (▼) marker of the Betti plot."""
        from PySide6.QtCore import QPoint, Qt
        from PySide6.QtTest import QTest

        panel = self.win.signatures_panel
        lines = [(line, markers) for line, markers in panel.marker_lines
                 if markers and line.axes is panel.figure.axes[0]]
        line, _markers = lines[int(self.flip) % len(lines)]
        x_data = line.get_xdata()[0]
        x, y = line.get_transform().transform((x_data, 1.0))
        ratio = panel.canvas.device_pixel_ratio
        position = QPoint(round(x / ratio), round((panel.figure.bbox.height - y) / ratio))
        QTest.mouseClick(panel.canvas, Qt.MouseButton.LeftButton, pos=position)

    def prepare(self, kind: str) -> None:
        """Where a kind starts from: Back/Forward need a visit to go back to."""
        if kind == "back_forward":
            self.model.set_index(self.model.index // 2 + 1)
            drain()
        if kind in ("arrow", "page"):
            self.model.set_index(self.model.default_index())
            drain()


def bare_render(plotter, render_window) -> float:
    """Seconds of one VTK render of the frame on screen, nothing else. pyvistaqt's widget
    answers a render made outside its paint with a repaint (a second render, which would
    land in the next step); marked as inside a paint, it does not."""
    inside = plotter._in_paint
    plotter._in_paint = True
    try:
        start = time.perf_counter()
        render_window.Render()
        return time.perf_counter() - start
    finally:
        plotter._in_paint = inside


def timed_steps(win, timer: PartTimer, kind: str, count: int) -> list[dict]:
    """`count` steps of one kind: each {"seconds", "bare", "parts", "changed"}, the bare
    render timed right after the step (the same frame, VTK only)."""
    stepper = Stepper(win)
    stepper.prepare(kind)
    render_window = win.scene.plotter.render_window
    rows = []
    for _ in range(count):
        before = win.model.index
        timer.reset()
        start = time.perf_counter()
        stepper.press(kind)
        drain()
        seconds = time.perf_counter() - start
        parts, renders = dict(timer.seconds), timer.renders
        bare = bare_render(win.scene.plotter, render_window)
        rows.append({"seconds": seconds, "bare": bare, "parts": parts, "renders": renders,
                     "changed": win.model.index != before})
    return rows


def drag(win, timer: PartTimer, seconds: float, span: int = 2000,
         shot: Callable[[], None] | None = None) -> dict:
    """Drag the slider's handle back and forth for `seconds` (each move handled and painted
    before the next, as fast as the window goes): frames per second, then the release and
    the time until the frame after it is painted. `shot()` runs once halfway (a picture of
    the window mid-drag; its time is left out of the frames per second)."""
    slider = win.alpha_panel.slider
    slider.setSliderDown(True)
    drain()
    start_position = slider.value()
    frames, positions = 0, 0
    timer.reset()
    start = time.perf_counter()
    step = max(span // 40, 1)
    while time.perf_counter() - start < seconds:
        if shot is not None and time.perf_counter() - start > seconds / 2:
            paused = time.perf_counter()
            shot()
            shot = None
            start += time.perf_counter() - paused
        positions += 1
        offset = (positions * step) % (2 * span)
        slider.setSliderPosition(start_position - min(offset, 2 * span - offset))
        renders = timer.renders
        drain()
        frames += timer.renders > renders
    elapsed = time.perf_counter() - start
    release = time.perf_counter()
    renders = timer.renders
    slider.setSliderDown(False)
    drain()
    return {"fps": frames / elapsed, "frames": frames, "moves": positions,
            "release_seconds": time.perf_counter() - release,
            "release_renders": timer.renders - renders}


def summary(rows: list[dict]) -> dict:
    """Median and 95th percentile of a kind's steps, its bare render and parts' shares."""
    seconds = sorted(row["seconds"] for row in rows)
    bare = statistics.median(row["bare"] for row in rows)
    total = sum(seconds) or 1.0
    parts: dict[str, float] = defaultdict(float)
    for row in rows:
        for part, spent in row["parts"].items():
            parts[part] += spent
    accounted = sum(parts.values())
    parts["other (Qt events, paints)"] = max(sum(seconds) - accounted, 0.0)
    return {"median": statistics.median(seconds), "p95": percentile(seconds, 95),
            "bare": bare, "steps": len(rows), "changed": sum(r["changed"] for r in rows),
            "renders_per_step": statistics.mean(r["renders"] for r in rows),
            "shares": {part: spent / total for part, spent in sorted(parts.items())}}


def percentile(values: list[float], q: float) -> float:
    """The q-th percentile of values (linear between ranks)."""
    ordered = sorted(values)
    if len(ordered) == 1:
        return ordered[0]
    rank = (len(ordered) - 1) * q / 100
    low = int(rank)
    high = min(low + 1, len(ordered) - 1)
    return ordered[low] + (ordered[high] - ordered[low]) * (rank - low)

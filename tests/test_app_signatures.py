"""The signatures dock: labelled log-alpha axes, a readout of the values under the mouse,
clickable optimal/suggested markers, and a persistence diagram with the current alpha."""

from __future__ import annotations

import itertools
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
from matplotlib.backend_bases import MouseEvent
from PySide6.QtCore import QPoint, Qt

from app.alpha_panel import AlphaPanel
from app.dataset import Dataset
from app.model import ExplorerModel, snap_index
from app.signatures_dock import SignaturesPanel, markers_of
from core import AlphaComplex


def ring_and_ball(n: int = 700, seed: int = 3) -> np.ndarray:
    """(n, 3) a noisy ring (a tunnel) beside a ball: several suggestions, varied Betti numbers."""
    rng = np.random.default_rng(seed)
    angle = rng.uniform(0, 2 * np.pi, n // 2)
    ring = np.column_stack([np.cos(angle), np.sin(angle), np.zeros(n // 2)])
    ring += rng.normal(scale=0.12, size=ring.shape)
    ball = rng.normal(scale=0.3, size=(n - n // 2, 3)) + np.array([3.0, 0.0, 0.0])
    return np.concatenate([ring, ball])


def make_dataset(points: np.ndarray) -> Dataset:
    """A built dataset of points (no file)."""
    ac = AlphaComplex.from_points(points)
    return Dataset(path=Path("p.npy"), ac=ac, spectrum=ac.spectrum(),
                   optimal_alpha=ac.optimal_alpha(), default_alpha=ac.default_alpha(),
                   signatures=ac.signatures(),
                   n_input=len(points), report=None, load_seconds=0.0, build_seconds=0.0)


@pytest.fixture(scope="module", params=[3, 2], ids=["3d", "2d"])
def dataset(request) -> Dataset:
    """A 3D ring and ball, or its 2D projection."""
    return make_dataset(ring_and_ball()[:, : request.param])


@pytest.fixture
def panels(qtbot, dataset):
    """A shown SignaturesPanel and an AlphaPanel on one model holding dataset."""
    model = ExplorerModel()
    signatures, alpha = SignaturesPanel(model), AlphaPanel(model)
    for widget in (signatures, alpha):
        qtbot.addWidget(widget)
    signatures.resize(1300, 320)
    signatures.show()
    qtbot.waitExposed(signatures)
    model.set_dataset(dataset)
    signatures.canvas.draw()
    return signatures, alpha


def display_to_qt(canvas, x: float, y: float) -> QPoint:
    """A matplotlib display point (pixels, origin bottom left) as a Qt widget position."""
    ratio = canvas.device_pixel_ratio
    return QPoint(round(x / ratio), round((canvas.figure.bbox.height - y) / ratio))


def marker_position(panel: SignaturesPanel, alpha: float, plot: int = 0) -> tuple[float, float]:
    """Display coordinates of the marker at alpha on signature plot `plot`."""
    line, _ = next(entry for entry in panel.marker_lines
                   if entry[0].axes is panel.figure.axes[plot]
                   and alpha in [m.alpha for m in entry[1]])
    return tuple(line.get_transform().transform((alpha, 1.0)))


def test_axes_are_log_alpha_with_units(panels, dataset) -> None:
    """The three signature plots share a log alpha axis labelled in data units."""
    panel, _ = panels
    axes = panel.figure.axes
    for ax in axes[:3]:
        assert ax.get_xscale() == "log"
        assert "alpha" in ax.get_xlabel() and "data units" in ax.get_xlabel()
        assert ax.get_ylabel()
    unit = "units³" if dataset.ac.dim == 3 else "units²"
    assert unit in axes[1].get_ylabel() or unit in axes[1].get_title()


def test_readout_gives_the_signatures_under_the_mouse(panels, dataset) -> None:
    """Moving the mouse over the Betti plot shows r, r² and the Betti numbers at that alpha."""
    panel, _ = panels
    sig = dataset.signatures
    ax = panel.figure.axes[0]
    for row in (len(sig.alphas) // 3, len(sig.alphas) // 2):
        alpha = float(np.sqrt(sig.alphas[row] * sig.alphas[row + 1]))  # inside entry row
        x, y = ax.transData.transform((alpha, 1.0))
        panel.canvas.callbacks.process(
            "motion_notify_event", MouseEvent("motion_notify_event", panel.canvas, x, y))
        text = panel.readout.text()
        assert f"r {alpha:.4g}" in text and f"r² {alpha * alpha:.4g}" in text
        for k, value in enumerate(sig.betti[row]):
            assert f"b{k} {int(value):,}" in text
        assert f"{sig.measure[row]:.4g}" in text


def test_markers_are_the_optimal_and_suggested_alphas(panels, dataset) -> None:
    """Each signature plot carries one optimal marker and the core's suggestions."""
    panel, _ = panels
    ac = dataset.ac
    optimal, suggested = markers_of(dataset)
    assert optimal.alpha == ac.optimal_alpha()
    assert [m.alpha for m in suggested] == [r.alpha for r in ac.suggest_alphas(5)]
    assert len(suggested) >= 2
    drawn = sorted(a for line, _ in panel.marker_lines for a in line.get_xdata())
    assert drawn == sorted([optimal.alpha, *[m.alpha for m in suggested]] * 3)


def test_markers_are_the_datasets_own_alphas(qtbot, dataset) -> None:
    """The markers are the optimal and suggested alphas the dataset holds (found with its
    topology off the GUI thread), not the complex's recomputed; without them, the complex's."""
    own = dataset.ac.suggest_alphas(5)
    given = replace(dataset, suggestions=own[::-2], optimal_alpha=own[0].alpha)
    optimal, suggested = markers_of(given)
    assert optimal.alpha == own[0].alpha
    assert [m.alpha for m in suggested] == [r.alpha for r in own[::-2]]
    assert "suggestion 1: Betti numbers" in suggested[0].text
    panel = SignaturesPanel(ExplorerModel())
    qtbot.addWidget(panel)
    panel.model.set_dataset(given)
    drawn = sorted(a for line, _ in panel.marker_lines for a in line.get_xdata())
    assert drawn == sorted([own[0].alpha, *[r.alpha for r in own[::-2]]] * 3)
    assert [m.alpha for m in markers_of(replace(dataset, suggestions=None))[1]] == [
        r.alpha for r in own]


@pytest.mark.parametrize("which", ["optimal", 0, 1])
def test_clicking_a_marker_moves_the_slider(panels, dataset, qtbot, which) -> None:
    """A left click on a marker moves the model and the slider to that alpha's shape."""
    panel, alpha_panel = panels
    optimal, suggested = markers_of(dataset)
    target = optimal if which == "optimal" else suggested[which]
    panel.model.set_index(0)
    before = alpha_panel.slider.value()
    x, y = marker_position(panel, target.alpha, plot=1)
    qtbot.mouseClick(panel.canvas, Qt.MouseButton.LeftButton, pos=display_to_qt(panel.canvas, x, y))
    spectrum = dataset.spectrum
    assert spectrum[panel.model.index] <= target.alpha < np.append(spectrum, np.inf)[
        panel.model.index + 1]
    assert alpha_panel.slider.value() != before
    if which == "optimal":
        assert panel.model.alpha == dataset.ac.optimal_alpha()
    assert panel.cursors[0].get_xdata()[0] == pytest.approx(panel.model.alpha)


def test_clicking_a_plot_away_from_markers_goes_to_that_alpha(panels, dataset, qtbot) -> None:
    """A click in a plot's body (not on a marker) moves alpha to the value under the mouse."""
    panel, _ = panels
    sig = dataset.signatures
    row = len(sig.alphas) // 4
    alpha = float(np.sqrt(sig.alphas[row] * sig.alphas[row + 1]))
    ax = panel.figure.axes[1]
    x, y = ax.transData.transform((alpha, 0.0))
    pos = display_to_qt(panel.canvas, x, y + 20)
    qtbot.mouseClick(panel.canvas, Qt.MouseButton.LeftButton, pos=pos)
    clicked = ax.transData.inverted().transform((pos.x() * panel.canvas.device_pixel_ratio, y))[0]
    assert panel.model.index == snap_index(dataset.spectrum, clicked)
    assert abs(panel.model.index - row) < len(sig.alphas) // 20


def test_persistence_diagram_and_its_alpha_lines(panels, dataset) -> None:
    """The diagram shows ac.persistence()'s pairs; the pairs left of / above the current-alpha
    lines (birth <= alpha < death) number b0 components and b_{d-1} holes/voids."""
    panel, _ = panels
    ac = dataset.ac
    persistence = ac.persistence()
    np.testing.assert_array_equal(panel.drawn_pairs[0].pairs, persistence.diagram(0))
    np.testing.assert_array_equal(panel.drawn_pairs[1].pairs, persistence.diagram(ac.dim - 1))
    assert panel.drawn_pairs[1].name == ("voids" if ac.dim == 3 else "holes")
    for index in np.linspace(1, len(dataset.spectrum) - 2, 7).astype(int):
        panel.model.set_index(int(index))
        alpha = panel.model.alpha
        assert panel.cursors[-1].get_xdata()[0] == alpha
        assert panel.death_cursor.get_ydata()[0] == alpha
        betti = ac.betti(alpha)
        for series, k in zip(panel.drawn_pairs, (0, ac.dim - 1), strict=True):
            alive = (series.pairs[:, 0] <= alpha) & (alpha < series.pairs[:, 1])
            assert int(alive.sum()) == betti[k]


def test_readout_names_the_pair_under_the_mouse(panels, dataset) -> None:
    """Hovering a point of the diagram names its series, birth and death."""
    panel, _ = panels
    ax = panel.persistence_ax
    birth, death = panel.drawn_pairs[1].pairs[0]
    x, y = ax.transData.transform((birth, death))
    event = MouseEvent("motion_notify_event", panel.canvas, x, y)
    text = panel.readout_text(event)
    assert f"born at r {birth:.4g}" in text and f"dies at r {death:.4g}" in text


def test_a_new_dataset_changes_data_not_the_figure(panels, dataset, monkeypatch) -> None:
    """The topology's arrival (on the GUI thread) keeps the axes, their artists and the fixed
    layout: no figure.clear, no layout engine, no mathtext tick labels to parse."""
    panel, _ = panels
    figure = panel.figure
    axes, steps, cursors = list(figure.axes), list(panel.steps), list(panel.cursors)
    positions = [ax.get_position().bounds for ax in axes]
    monkeypatch.setattr(figure, "clear", lambda *a, **k: pytest.fail("figure cleared"))
    other = make_dataset(ring_and_ball(500, seed=8)[:, : dataset.ac.dim])
    panel.model.set_dataset(other)
    panel.canvas.draw()
    assert figure.get_layout_engine() is None
    assert figure.axes == axes and panel.steps == steps and panel.cursors == cursors
    assert [ax.get_position().bounds for ax in axes] == positions
    np.testing.assert_array_equal(panel.drawn_pairs[0].pairs,
                                  other.ac.persistence().diagram(0))
    labels = [t.get_text() for ax in axes for axis in (ax.xaxis, ax.yaxis)
              for t in axis.get_ticklabels()]
    assert any(labels) and not any("$" in text for text in labels)


def test_margins_are_fixed_in_points_whatever_the_size(panels) -> None:
    """Resizing moves the axes to the same margins in points (no text is measured)."""
    from app.signature_figure import LEFT_PT, TOP_PT

    panel, _ = panels
    for width, height in ((900, 240), (1500, 420)):
        panel.resize(width, height)
        panel.canvas.draw()
        box, dpi = panel.figure.bbox, panel.figure.dpi
        left = panel.figure.axes[0].get_position()
        assert left.x0 * box.width == pytest.approx(LEFT_PT * dpi / 72, rel=1e-6)
        assert (1 - left.y1) * box.height == pytest.approx(TOP_PT * dpi / 72, rel=1e-6)


def flush_events(qtbot) -> None:
    """Let every queued event run (the slider's coalescing timer, a pending draw, paints)."""
    for _ in range(3):
        qtbot.wait(5)


def cursor_pixel_gap(panel, x_data: float) -> float:
    """How far (0..255) the canvas's pixels near the cursor line at x_data, halfway up the
    Betti plot, are from the cursor colour: about 0 where the line is drawn."""
    from matplotlib.colors import to_rgb

    from app.signature_figure import CURSOR_COLOUR

    ax = panel.figure.axes[0]
    x, y = ax.transAxes.transform((0.0, 0.5))
    x = ax.transData.transform((x_data, 1.0))[0]
    image = np.asarray(panel.canvas.buffer_rgba())[:, :, :3].astype(float)
    row, column = int(image.shape[0] - y), round(float(x))
    near = image[row, column - 1: column + 2]
    return float(np.abs(near - 255 * np.array(to_rgb(CURSOR_COLOUR))).max(axis=1).min())


def test_slider_steps_move_the_cursors_without_a_full_redraw(panels, qtbot) -> None:
    """Arrow-key steps move the cursors over the figure's cached pixels: no full draw of the
    figure (axes, ticks, legends, text), and the picture shows the cursor at the new alpha,
    none at the old one."""
    panel, alpha_panel = panels
    model = panel.model
    model.set_index(3 * len(model.spectrum) // 4)
    flush_events(qtbot)
    old = float(panel.plot_x(np.array([model.alpha]))[0])
    draws = []
    panel.canvas.mpl_connect("draw_event", draws.append)
    start = model.index
    for key in (Qt.Key.Key_Left, Qt.Key.Key_Left, Qt.Key.Key_PageDown, Qt.Key.Key_PageDown):
        qtbot.keyClick(alpha_panel.slider, key)
        flush_events(qtbot)
    assert model.index < start - 2
    assert draws == []
    new = float(panel.plot_x(np.array([model.alpha]))[0])
    assert panel.cursors[0].get_xdata()[0] == new
    new_x, old_x = (panel.figure.axes[0].transData.transform((v, 1.0))[0] for v in (new, old))
    assert abs(new_x - old_x) > 3  # far enough apart to tell the two places apart
    assert cursor_pixel_gap(panel, new) < 40
    assert cursor_pixel_gap(panel, old) > 40


@pytest.mark.parametrize("decades", [3, 8, 12])
@pytest.mark.parametrize("weighted", [True, False])
def test_alpha_tick_labels_do_not_overlap_at_the_window_width(weighted, decades):
    """The alpha axis of each signature plot, over a few to many decades at the width the
    window gives it (1280 pixels for the four plots), has labels that do not run into each
    other."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    from app.signature_figure import new_figure, set_alpha_scale

    figure, axes = new_figure()
    figure.set_size_inches(12.8, 1.8)
    canvas = FigureCanvasAgg(figure)
    x = np.concatenate([-np.logspace(2, 0, 20), [0.0], np.logspace(-5, decades - 5, 60)])
    if not weighted:
        x = x[x > 0]
    for ax in axes[:3]:
        ax.set_visible(True)
        ax.plot(x, np.arange(len(x)))
        set_alpha_scale(ax, weighted, 1.0)
    canvas.draw()
    renderer = canvas.get_renderer()
    for ax in axes[:3]:
        boxes = sorted((t.get_window_extent(renderer) for t in ax.get_xticklabels()
                        if t.get_text() and t.get_visible()), key=lambda b: b.x0)
        assert len(boxes) >= 2
        assert all(a.x1 < b.x0 for a, b in itertools.pairwise(boxes)), ax.get_xticklabels()

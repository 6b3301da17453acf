"""Moving the alpha cursor of the signature plots: a full matplotlib draw, matplotlib blitting
and pyqtgraph, on the same data in one run (the choice app/plot_blit.py rests on).

    xvfb-run -a python benchmarks/bench_plot_cursor.py [--n 20000] [--moves 30] [--no-save]

The data: the signatures of a noisy torus of n points (datasets.noisy_torus). Each way moves
the cursors to `moves` alphas and paints the widget synchronously (`repaint`), at 1280 x 260:
- full draw: the real SignaturesPanel as it was: cursor data set, the whole figure drawn;
- blit: the real SignaturesPanel now (restore the cached background, draw the cursors, blit);
- pyqtgraph: four PlotItems with the same step curves (log alpha), legends and titles and
  one InfiniteLine per plot moved with setValue (skipped when pyqtgraph is not installed).
Figures: the median seconds per move, each against the full draw measured in the same run.
"""

from __future__ import annotations

import os
import statistics
import sys
import time
from pathlib import Path

os.environ["QT_API"] = "pyside6"
sys.path.insert(0, str(Path(__file__).resolve().parent))
sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

import numpy as np

SIZE = (1280, 260)


def timed_moves(move, alphas: np.ndarray) -> list[float]:
    """Seconds of move(alpha) for each alpha (a first, untimed move warms caches)."""
    move(float(alphas[0]))
    times = []
    for alpha in alphas:
        start = time.perf_counter()
        move(float(alpha))
        times.append(time.perf_counter() - start)
    return times


def built_dataset(points: np.ndarray):
    """A Dataset of points with its topology, built here (no file, no window)."""
    from app.dataset import Dataset
    from core import AlphaComplex

    ac = AlphaComplex.from_points(points)
    return Dataset(path=Path("torus.npy"), ac=ac, spectrum=ac.spectrum(),
                   optimal_alpha=ac.optimal_alpha(), default_alpha=ac.default_alpha(),
                   signatures=ac.signatures(), n_input=len(points), report=None,
                   load_seconds=0.0, build_seconds=0.0)


def signatures_panel(dataset):
    """A shown SignaturesPanel on a model holding dataset, drawn once."""
    from PySide6.QtWidgets import QApplication

    from app.model import ExplorerModel
    from app.signatures_dock import SignaturesPanel

    panel = SignaturesPanel(ExplorerModel())
    panel.resize(*SIZE)
    panel.show()
    panel.model.set_dataset(dataset)
    panel.canvas.draw()
    QApplication.processEvents()
    return panel


def matplotlib_moves(panel, alphas: np.ndarray, full: bool) -> list[float]:
    """Seconds per cursor move of the real panel: blitted, or with a full figure draw."""
    model = panel.model

    def move(alpha: float) -> None:
        model.set_alpha(alpha)  # the panel's move_cursor draws the cursors over its cache
        if full:
            panel.canvas.draw()
        panel.canvas.repaint()  # the paint itself, synchronously, as the other ways

    return timed_moves(move, alphas)


def pyqtgraph_moves(sig, alphas: np.ndarray) -> list[float] | None:
    """Seconds per cursor move of a pyqtgraph figure like the signatures one (None when
    pyqtgraph is not installed), measured in a child process: pyqtgraph 0.14 with PySide6
    6.12 aborts at interpreter exit, and a multiprocessing child leaves without one."""
    import multiprocessing as mp

    columns = (np.asarray(sig.alphas), sig.betti, sig.measure, sig.boundary_measure)
    with mp.get_context("spawn").Pool(1) as pool:
        return pool.apply(_pyqtgraph_moves, (*columns, alphas))


def _pyqtgraph_moves(sig_alphas, betti, measure, boundary, alphas) -> list[float] | None:
    """pyqtgraph_moves in the child (the signature columns as plain arrays)."""
    try:
        import pyqtgraph as pg
    except ImportError:
        return None
    from types import SimpleNamespace

    from PySide6.QtWidgets import QApplication

    from app.signature_figure import log_samples

    QApplication.instance() or QApplication([])
    sig = SimpleNamespace(alphas=sig_alphas, betti=betti, measure=measure,
                          boundary_measure=boundary)
    widget = pg.GraphicsLayoutWidget()
    widget.resize(*SIZE)
    rows = log_samples(np.asarray(sig.alphas))
    x = np.log10(np.asarray(sig.alphas)[rows])
    lines = []
    columns = ([sig.betti[rows, k] for k in range(sig.betti.shape[1])], [sig.measure[rows]],
               [sig.boundary_measure[rows]], [sig.betti[rows, 0]])
    for title, ys in zip(("Betti numbers", "measure", "boundary", "persistence"), columns,
                         strict=True):
        plot = widget.addPlot(title=title)
        plot.addLegend()
        plot.setLabel("bottom", "alpha (radius, data units)")
        for k, y in enumerate(ys):
            plot.plot(np.append(x, x[-1] + 1e-3), y, stepMode="center", name=f"b{k}",
                      pen=pg.intColor(k))
        line = pg.InfiniteLine(angle=90, pen=pg.mkPen("#444444"))
        plot.addItem(line)
        lines.append(line)
    widget.show()
    widget.repaint()

    def move(alpha: float) -> None:
        for line in lines:
            line.setValue(np.log10(alpha))
        QApplication.processEvents()  # the scene's change notice is queued
        widget.viewport().repaint()

    times = timed_moves(move, alphas)
    widget.close()
    return times


def run(n: int, moves: int) -> dict:
    """Median seconds per move of the three ways on one torus's signatures."""
    from datasets import noisy_torus
    from PySide6.QtWidgets import QApplication

    QApplication.instance() or QApplication([])
    dataset = built_dataset(noisy_torus(n, seed=0))
    spectrum = dataset.spectrum
    picks = np.linspace(len(spectrum) // 4, len(spectrum) - 2, moves).round().astype(np.int64)
    alphas = spectrum[picks]
    panel = signatures_panel(dataset)
    result = {"n": n, "moves": moves,
              "full_draw": statistics.median(matplotlib_moves(panel, alphas, full=True)),
              "blit": statistics.median(matplotlib_moves(panel, alphas[::-1], full=False))}
    qtgraph = pyqtgraph_moves(dataset.signatures, alphas)
    result["pyqtgraph"] = statistics.median(qtgraph) if qtgraph else None
    panel.close()
    return result


def figures(result: dict) -> list:
    """The benchmark's figures: each way per move, against the full draw of the same run."""
    from results import Figure

    full = result["full_draw"]
    out = [Figure("plot_cursor.blit", "cursor move, matplotlib blit (real signatures dock)",
                  result["blit"], "s", "full matplotlib draw per move", full, "<= 0.05")]
    if result["pyqtgraph"] is not None:
        out.append(Figure("plot_cursor.pyqtgraph", "cursor move, pyqtgraph InfiniteLine",
                          result["pyqtgraph"], "s", "full matplotlib draw per move", full))
    return out


def main(argv: list[str] | None = None) -> None:
    """Run, print the medians and save the result (benchmarks/results/plot_cursor.json)."""
    import argparse

    from results import save

    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--n", type=int, default=20_000)
    parser.add_argument("--moves", type=int, default=30)
    parser.add_argument("--no-save", action="store_true")
    args = parser.parse_args(argv)
    result = run(args.n, args.moves)
    for way in ("full_draw", "blit", "pyqtgraph"):
        value = result[way]
        print(f"{way:10s} {'-' if value is None else f'{value * 1000:8.2f} ms'} per move")
    if not args.no_save:
        save("plot_cursor", figures(result), notes=[
            f"Signatures of a {result['n']:,}-point noisy torus, {result['moves']} cursor "
            f"moves at {SIZE[0]} x {SIZE[1]} pixels, each painted synchronously (repaint).",
            "pyqtgraph has no symmetric-log axis (weighted points' alpha²): the dock keeps "
            "matplotlib and blits its cursors."])


if __name__ == "__main__":
    main()

"""Benchmark of a slider step in the explorer (issue 6, Performance).

    python benchmarks/bench_slider.py [--n 200000] [--steps 40] [--seed 0] [--size 1280x800]
        [--all-layers] [--json out.json]

A step is what the window does when the alpha index moves: `cursor.move(alpha)` (the
dataset's ShapeCursor, as app.model uses it) plus swapping the connectivity of the visible
layers' persistent meshes (app.scene.Scene.set_shape). Steps: arrow keys (next critical
value), a mouse drag over a 1000-pixel slider (spectrum/1000 per pixel) and Page keys
(spectrum/50). The render is timed apart: here it is software rendering (llvmpipe), on a
desktop GPU it is not. Every figure is reported as a ratio to the table build time measured
in the same run; the cursor's one-off set-up (done in the loader thread) is reported too.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import sys
import tempfile
import time
from dataclasses import replace
from pathlib import Path

os.environ.setdefault("VTK_DEFAULT_OPENGL_WINDOW", "vtkEGLRenderWindow")
sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

import numpy as np
import pyvista as pv
from datasets import noisy_torus

from app.palette import default_styles
from app.scene import Scene, as_xyz
from core import AlphaComplex


def parse_args(argv: list[str] | None = None) -> argparse.Namespace:
    """Command-line options."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--n", type=int, default=200_000, help="torus points (default 200000)")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--steps", type=int, default=40, help="slider steps of each kind")
    parser.add_argument("--size", default="1280x800", help="render window WxH")
    parser.add_argument("--all-layers", action="store_true",
                        help="also update the interior (cells) layer, hidden by default in 3D")
    parser.add_argument("--json", help="write the figures to this JSON file")
    return parser.parse_args(argv)


def timed(fn) -> float:
    """Wall seconds of one call of fn()."""
    start = time.perf_counter()
    fn()
    return time.perf_counter() - start


def step_times(cursor, spectrum: np.ndarray, scene: Scene, indexes: np.ndarray) -> list[float]:
    """Seconds per step (shape query + scene update, no render) over the alpha indexes."""
    return [timed(lambda i=i: scene.set_shape(cursor.move(float(spectrum[i]))))
            for i in indexes]


def rerender(plotter: pv.Plotter) -> None:
    """One full software render of the scene (marks it modified first, so VTK redraws)."""
    plotter.renderer.Modified()
    plotter.render_window.Render()


def summary(times: list[float]) -> dict[str, float]:
    """Median and worst of a list of seconds."""
    return {"median_s": statistics.median(times), "max_s": max(times)}


def run(args: argparse.Namespace) -> dict:
    """Build once, then time arrow-key steps, page steps and renders."""
    points = noisy_torus(args.n, seed=args.seed)
    AlphaComplex.from_points(points[:50])
    started = time.perf_counter()
    ac = AlphaComplex.from_points(points)
    build_s = time.perf_counter() - started
    spectrum = ac.spectrum()
    start = int(np.searchsorted(spectrum, ac.optimal_alpha(), side="right")) - 1
    start = min(max(start, 0), len(spectrum) - 2 * args.steps - 1)
    page, pixel = max(1, len(spectrum) // 50), max(1, len(spectrum) // 1000)
    started = time.perf_counter()
    cursor = ac.cursor()
    cursor_s = time.perf_counter() - started
    width, height = (int(v) for v in args.size.lower().split("x"))
    plotter = pv.Plotter(off_screen=True, window_size=[width, height])
    try:
        styles = default_styles(ac.dim)
        if args.all_layers:
            styles["interior"] = replace(styles["interior"], visible=True)
        scene = Scene(plotter)
        scene.set_dataset(as_xyz(ac.to_ambient(ac.points)), ac.dim, ac.simplices(1), styles)
        scene.set_shape(cursor.move(float(spectrum[start])))
        plotter.render_window.Render()
        steps = 1 + np.arange(args.steps)
        arrows = step_times(cursor, spectrum, scene, start + steps)
        drags = step_times(cursor, spectrum, scene, (start + pixel * steps) % len(spectrum))
        pages = step_times(cursor, spectrum, scene, (start + page * steps) % len(spectrum))
        renders = [timed(lambda: rerender(plotter)) for _ in range(5)]
    finally:
        plotter.close()
    return {
        "n_points": args.n, "n_cells": len(ac.simplices(ac.dim)), "spectrum": len(spectrum),
        "build_s": build_s, "cursor_setup_s": cursor_s, "arrow_step": summary(arrows),
        "drag_step": summary(drags), "page_step": summary(pages),
        "render": summary(renders), "window": args.size, "all_layers": args.all_layers,
    }


def report(figures: dict) -> str:
    """Human-readable lines with the goal ratio (step / build <= 1/1000)."""
    build = figures["build_s"]
    lines = [f"{figures['n_points']:,} points, {figures['n_cells']:,} cells, "
             f"{figures['spectrum']:,} critical alphas; table build {build:.2f} s; "
             f"cursor set-up {figures['cursor_setup_s']:.2f} s (loader thread, once)"]
    for kind in ("arrow_step", "drag_step", "page_step"):
        median, worst = figures[kind]["median_s"], figures[kind]["max_s"]
        lines.append(f"{kind:10s} median {1e3 * median:8.3f} ms  worst {1e3 * worst:8.3f} ms  "
                     f"median/build 1/{build / median:,.0f}  worst/build 1/{build / worst:,.0f}")
    render = figures["render"]
    lines.append(f"render     median {1e3 * render['median_s']:8.1f} ms (software, "
                 f"{figures['window']}; not part of the step)")
    return "\n".join(lines)


def write_json(path: Path, figures: dict) -> None:
    """Write figures as JSON atomically (temp file + os.replace)."""
    fd, tmp = tempfile.mkstemp(dir=path.resolve().parent, suffix=".json")
    with os.fdopen(fd, "w") as stream:
        json.dump(figures, stream, indent=2)
    os.replace(tmp, path)


def main(argv: list[str] | None = None) -> int:
    """Run, print, optionally write JSON."""
    args = parse_args(argv)
    figures = run(args)
    print(report(figures))
    if args.json:
        write_json(Path(args.json), figures)
    return 0


if __name__ == "__main__":
    sys.exit(main())

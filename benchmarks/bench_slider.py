"""Benchmark of a slider step in the explorer: shape query + mesh update against the build.

    python benchmarks/bench_slider.py [--n 200000] [--steps 40] [--seed 0] [--size 1280x800]
        [--all-layers] [--skip-open3d] [--json out.json]

A step is what the window does when the alpha index moves: `cursor.move(alpha)` (the
dataset's ShapeCursor, as app.model uses it) plus swapping the connectivity of the visible
layers' persistent meshes (app.scene.Scene.set_shape). Steps: arrow keys (next critical
value), a mouse drag over a 1000-pixel slider (spectrum/1000 per pixel) and Page keys
(spectrum/50), each kind going on from where the last stopped and turning at the ends. The
render is timed apart: here it is software rendering (llvmpipe), on a desktop GPU it is not.
Every figure is reported as a ratio to the table build time measured
in the same run; the cursor's one-off set-up (done in the loader thread) is reported too.
When `import open3d` works, Open3D's per-alpha reconstruction (TetraMesh made once, then
create_from_point_cloud_alpha_shape) is timed on the same points at the first arrow and page
alphas, and the slowest step of each kind is given as a ratio to Open3D's fastest alpha.
The step figures go to benchmarks/results/bench_slider.json (benchmarks/results.py).
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
from results import Figure, save

from app.palette import default_styles
from app.scene import Scene, SceneData, as_xyz
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
    parser.add_argument("--skip-open3d", action="store_true", help="do not time Open3D")
    parser.add_argument("--json", help="write the figures to this JSON file")
    return parser.parse_args(argv)


def timed(fn) -> float:
    """Wall seconds of one call of fn()."""
    start = time.perf_counter()
    fn()
    return time.perf_counter() - start


def clocked(fn) -> tuple[float, float]:
    """Wall and CPU seconds of one call of fn()."""
    start, cpu = time.perf_counter(), time.process_time()
    fn()
    return time.perf_counter() - start, time.process_time() - cpu


def step_times(cursor, spectrum: np.ndarray, scene: Scene, indexes: np.ndarray) -> dict:
    """Median and worst seconds per step (shape query + scene update, no render) over the
    alpha indexes, on the wall clock and on the CPU clock."""
    walls, cpus = zip(*(clocked(lambda i=i: scene.set_shape(cursor.move(float(spectrum[i]))))
                        for i in indexes), strict=True)
    cpu = summary(list(cpus))
    return summary(list(walls)) | {"cpu_median_s": cpu["median_s"], "cpu_max_s": cpu["max_s"]}


def bounce(indexes: np.ndarray, length: int) -> np.ndarray:
    """Indexes folded back into [0, length) at both ends, as a user paging on would turn."""
    period = 2 * (length - 1)
    folded = np.asarray(indexes) % period
    return np.where(folded < length, folded, period - folded)


def rerender(plotter: pv.Plotter) -> None:
    """One full software render of the scene (marks it modified first, so VTK redraws)."""
    plotter.renderer.Modified()
    plotter.render_window.Render()


def open3d_times(points: np.ndarray, alphas: list[float]) -> dict | None:
    """Open3D's alpha shape at each alpha (a radius, as ours) after one TetraMesh; None when
    open3d does not import."""
    try:
        import open3d as o3d
    except ImportError:
        return None
    cloud = o3d.geometry.PointCloud(o3d.utility.Vector3dVector(points))
    started = time.perf_counter()
    tetra, pt_map = o3d.geometry.TetraMesh.create_from_point_cloud(cloud)
    tetra_s = time.perf_counter() - started
    create = o3d.geometry.TriangleMesh.create_from_point_cloud_alpha_shape
    per_alpha = []
    for alpha in alphas:
        started = time.perf_counter()
        mesh = create(cloud, alpha, tetra, pt_map)
        per_alpha.append({"alpha": alpha, "seconds": time.perf_counter() - started,
                          "triangles": len(mesh.triangles)})
    return {"version": o3d.__version__, "tetra_mesh_s": tetra_s, "per_alpha": per_alpha}


def summary(times: list[float]) -> dict[str, float]:
    """Median and worst of a list of seconds."""
    return {"median_s": statistics.median(times), "max_s": max(times)}


def run(args: argparse.Namespace) -> dict:
    """Build once, then time arrow-key steps, page steps and renders."""
    points = noisy_torus(args.n, seed=args.seed)
    AlphaComplex.from_points(points[:50])
    started, started_cpu = time.perf_counter(), time.process_time()
    ac = AlphaComplex.from_points(points)
    build_s, build_cpu_s = time.perf_counter() - started, time.process_time() - started_cpu
    spectrum = ac.spectrum()
    start = int(np.searchsorted(spectrum, ac.optimal_alpha(), side="right")) - 1
    start = min(max(start, 0), len(spectrum) - 2 * args.steps - 1)
    page, pixel = max(1, len(spectrum) // 50), max(1, len(spectrum) // 1000)
    started = time.perf_counter()
    cursor = ac.cursor()
    cursor_s = time.perf_counter() - started
    width, height = (int(v) for v in args.size.lower().split("x"))
    scene = Scene.off_screen((width, height))
    plotter = scene.plotter  # the benchmark times the scene's own renders
    try:
        styles = default_styles(ac.dim)
        if args.all_layers:
            styles["interior"] = replace(styles["interior"], visible=True)
        scene.set_dataset(SceneData(as_xyz(ac.to_ambient(ac.points)), ac.dim, ac.simplices(1),
                                    styles))
        scene.set_shape(cursor.move(float(spectrum[start])))
        plotter.render_window.Render()
        steps = 1 + np.arange(args.steps)
        arrows = step_times(cursor, spectrum, scene, start + steps)
        drags = step_times(cursor, spectrum, scene, bounce(start + pixel * steps, len(spectrum)))
        pages = step_times(cursor, spectrum, scene, bounce(start + page * steps, len(spectrum)))
        renders = [timed(lambda: rerender(plotter)) for _ in range(5)]
    finally:
        scene.close()
    open3d = None if args.skip_open3d else open3d_times(
        points, [float(spectrum[start + 1]),
                 float(spectrum[bounce(start + page, len(spectrum))])])
    return {
        "n_points": args.n, "n_cells": len(ac.simplices(ac.dim)), "spectrum": len(spectrum),
        "build_s": build_s, "build_cpu_s": build_cpu_s, "cursor_setup_s": cursor_s,
        "arrow_step": arrows, "drag_step": drags, "page_step": pages,
        "render": summary(renders), "window": args.size, "all_layers": args.all_layers,
        "steps": args.steps,
        "open3d": open3d,
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
    if figures.get("open3d"):
        o3d = figures["open3d"]
        fastest = min(entry["seconds"] for entry in o3d["per_alpha"])
        for entry in o3d["per_alpha"]:
            lines.append(f"Open3D {o3d['version']} alpha {entry['alpha']:.6g}: "
                         f"{entry['seconds']:.3f} s, {entry['triangles']:,} triangles "
                         f"(TetraMesh once: {o3d['tetra_mesh_s']:.2f} s)")
        for kind in ("arrow_step", "drag_step", "page_step"):
            worst = figures[kind]["max_s"]
            lines.append(f"{kind:10s} worst / Open3D's fastest alpha = {worst / fastest:.5f} "
                         f"(goal <= 0.1)")
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


STEP_GOAL = "<= 0.001"  # a slider step at most a thousandth of the table's build
KINDS = {"arrow_step": "arrow key (next critical alpha)", "drag_step": "mouse drag (1 pixel)",
         "page_step": "Page key (1/50 of the spectrum)"}


def result_figures(figures: dict) -> list[Figure]:
    """The median and the worst step of each kind against the build of the same run, on the
    wall and on the CPU clock."""
    n = f"{figures['n_points']:,} torus points"
    return [Figure(name=f"{kind}_{stat}_{clock}", label=f"slider step, {label}, {stat} of "
                   f"{figures['steps']}, {word}, {n}", value=figures[kind][f"{prefix}{stat}_s"],
                   unit="s", anchor="table build", anchor_value=figures[build], goal=STEP_GOAL)
            for kind, label in KINDS.items() for stat in ("median", "max")
            for clock, word, prefix, build in (("wall", "wall", "", "build_s"),
                                               ("cpu", "CPU", "cpu_", "build_cpu_s"))]


def main(argv: list[str] | None = None) -> int:
    """Run, print, write the result (and the detailed JSON when asked)."""
    args = parse_args(argv)
    figures = run(args)
    print(report(figures))
    if args.json:
        write_json(Path(args.json), figures)
    save("bench_slider", result_figures(figures), notes=[
        "A step is the window's cursor.move(alpha) plus the swap of the visible layers' mesh "
        "connectivity, without the render; the anchor is the table build of the same run. "
        f"Render alone (software, {figures['window']}): median "
        f"{1e3 * figures['render']['median_s']:.1f} ms."])
    return 0


if __name__ == "__main__":
    sys.exit(main())

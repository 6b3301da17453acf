"""Drawing 20,000 balls (atoms, weighted points): sphere impostors against plain points and
against the tessellated sphere glyphs they replace, in one run.

    xvfb-run -a python benchmarks/bench_balls.py [--copies 36] [--size 685x454] [--no-save]

The balls: a synthetic protein (bench_molecule.write_copies: rotated copies of the shared
1A8O, 556 atoms each; 36 copies = 20,016 atoms) at van der Waals radii, fitted in a view the
size of the window's 3D view. Each way is one actor in an off-screen plotter, timed as the
median of full renders (`render_window.Render()` after `Modified()`), software GL here:
- impostors: app.scene.layers.ball_mesh + ball_actor (what the window draws);
- plain points: the same centres as the points layer draws them (3 px);
- same-pixel points: square points as wide as the balls' mean diameter on screen (the
  impostors' own fill, without their sphere shading and depth);
- glyphs: the sphere glyphs drawn before (10 x 10 facets a ball).
"""

from __future__ import annotations

import argparse
import statistics
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

import numpy as np

RENDERS = 5


def render_ms(plotter) -> float:
    """Median milliseconds of RENDERS full renders of plotter (after one untimed)."""
    window = plotter.render_window
    window.Render()
    times = []
    for _ in range(RENDERS):
        plotter.renderer.Modified()
        start = time.perf_counter()
        window.Render()
        times.append(time.perf_counter() - start)
    return 1000 * statistics.median(times)


def ball_pixels(plotter, radii: np.ndarray) -> float:
    """The balls' mean diameter on screen (pixels) in plotter's fitted view."""
    camera = plotter.renderer.GetActiveCamera()
    distance = camera.GetDistance()
    height = plotter.window_size[1]
    view_height = 2 * distance * np.tan(np.radians(camera.GetViewAngle() / 2))
    return float(2 * radii.mean() * height / view_height)


def protein(copies: int) -> tuple[np.ndarray, np.ndarray]:
    """(centres (n, 3), van der Waals radii (n,)) of bench_molecule's rotated copies of 1A8O."""
    import tempfile

    from bench_molecule import write_copies

    from core.io.molecule import read_molecule

    with tempfile.TemporaryDirectory(prefix="alphascoop-balls-") as folder:
        path = Path(folder) / "copies.pdb"
        write_copies(copies, path)
        molecule = read_molecule(path)
    return molecule.centres, molecule.vdw_radii


def run(copies: int, size: tuple[int, int]) -> dict:
    """Milliseconds per render of each way on the same balls."""
    import pyvista as pv

    from app.scene.layers import ball_actor, ball_mesh

    centres, radii = protein(copies)
    plotter = pv.Plotter(off_screen=True, window_size=list(size))
    impostors = ball_actor(ball_mesh(centres, radii, limit=len(centres)), "#8fb8de", 1.0)
    plotter.add_actor(impostors, reset_camera=True, render=False)
    cloud = pv.PolyData(centres)
    plain = plotter.add_mesh(cloud, color="#c9d1d9", point_size=3.0, style="points",
                             render=False, reset_camera=False)
    pixels = ball_pixels(plotter, radii)
    wide = plotter.add_mesh(cloud.copy(), color="#c9d1d9", point_size=pixels, style="points",
                            render=False, reset_camera=False)
    cloud["radius"] = radii
    sphere = pv.Sphere(radius=1.0, theta_resolution=10, phi_resolution=10)
    glyphs = plotter.add_mesh(cloud.glyph(scale="radius", geom=sphere, orient=False),
                              color="#8fb8de", render=False, reset_camera=False)
    actors = {"impostors": impostors, "plain_points": plain, "same_pixel_points": wide,
              "glyphs": glyphs}
    result = {"balls": len(centres), "size": size, "ball_pixels": pixels}
    for name, actor in actors.items():
        for other in actors.values():
            other.SetVisibility(other is actor)
        result[name] = render_ms(plotter)
    plotter.screenshot(None)  # the glyphs drawn last: nothing to keep
    plotter.close()
    return result


def figures(result: dict) -> list:
    """Impostors against plain points (the goal), same-pixel points and the old glyphs."""
    from results import Figure

    n = f"{result['balls']:,}"
    return [
        Figure("balls.impostors_vs_points", f"{n} balls (sphere impostors), one render",
               result["impostors"], "ms", f"{n} plain points (3 px)", result["plain_points"],
               "<= 2"),
        Figure("balls.impostors_vs_same_pixels", f"{n} balls (sphere impostors), one render",
               result["impostors"], "ms",
               f"{n} square points {result['ball_pixels']:.0f} px wide (the balls' fill)",
               result["same_pixel_points"]),
        Figure("balls.glyphs_vs_impostors", f"{n} tessellated sphere glyphs, one render",
               result["glyphs"], "ms", f"{n} sphere impostors", result["impostors"]),
    ]


def main(argv: list[str] | None = None) -> None:
    """Run, print the milliseconds and save benchmarks/results/balls.json."""
    from results import save

    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--copies", type=int, default=36)
    parser.add_argument("--size", default="685x454", help="view W x H (the window's 3D view)")
    parser.add_argument("--no-save", action="store_true")
    args = parser.parse_args(argv)
    size = tuple(int(v) for v in args.size.split("x"))
    result = run(args.copies, size)
    for name in ("impostors", "plain_points", "same_pixel_points", "glyphs"):
        print(f"{name:18s} {result[name]:9.1f} ms")
    print(f"balls {result['balls']:,}, {result['ball_pixels']:.1f} px wide on screen")
    if not args.no_save:
        save("balls", figures(result), notes=[
            f"A synthetic protein of {result['balls']:,} atoms (rotated copies of 1A8O) at "
            f"van der Waals radii, fitted in a {size[0]} x {size[1]} view, software GL "
            f"(llvmpipe, no multisampling in an off-screen plotter); median of {RENDERS} "
            "full renders each.",
            "Balls cover far more pixels than 3-pixel points: on a software renderer the "
            "fill (overdraw of overlapping atoms) is the cost, as the same-pixel square "
            "points show."])


if __name__ == "__main__":
    main()

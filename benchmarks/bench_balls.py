"""Drawing 20,000 balls (atoms, weighted points): what the window draws against plain points,
against the balls drawn before and against tessellated sphere glyphs, in one run.

    xvfb-run -a python benchmarks/bench_balls.py [--copies 36] [--size 685x454] [--no-save]

The balls: a synthetic protein (bench_molecule.write_copies: rotated copies of the shared
1A8O, 556 atoms each; 36 copies = 20,016 atoms) at the radii a molecule opens with in the
window (van der Waals + the 1.4 Å probe: the balls its measures are of), fitted in a view
the size of the window's 3D view, drawn as the window draws (app.scene.interactive: one
sample a pixel, FXAA). Each way is one actor in an off-screen plotter, timed as the median
of full renders (`render_window.Render()` after `Modified()`), one of each way in turn (a
change of the machine's load falls on all alike), software GL here:
- balls: app.scene as the window draws an opaque, uncut molecule in a still view (a slider
  step): sphere impostors lit from the eye (BALL_LIGHT), of the balls with exposed area
  (outer_balls: exact per-atom areas of measure_molecule at the drawn radii) only those the
  view shows (app.scene.seen_balls: an id pass finds them once per view);
- new view: the same after the view changed, its id pass in the render (the window paints
  a new view with every outer ball first and runs the pass after);
- outer: every ball with exposed area, lit from the eye (what was drawn before the id pass);
- every ball, lit from the eye (what clipping or translucency draws);
- before: every ball under the renderer's light kit (the impostors as first drawn);
- van der Waals: the balls at van der Waals radii as the window draws them in a still view;
- plain points: the same centres as the points layer draws them (3 px);
- same-pixel points: square points as wide as the balls' mean diameter on screen (the fill
  of every ball, without sphere shading and depth);
- glyphs: the sphere glyphs drawn before the impostors (10 x 10 facets a ball).
The balls and plain points are timed again without FXAA.
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
PROBE = 1.4  # Å: the window's molecule balls are van der Waals + probe
COLOUR = "#8fb8de"


def render_ms(plotter, actors: dict, before: dict | None = None) -> dict[str, float]:
    """Median milliseconds of RENDERS full renders of plotter with each of actors alone,
    taken in turns (one render of each a round, after one untimed each), so a change in the
    machine's load falls on every way alike; before[name]() runs ahead of each of its
    renders, untimed."""
    window = plotter.render_window
    times: dict[str, list[float]] = {name: [] for name in actors}
    for timed in [False] + [True] * RENDERS:
        for name, actor in actors.items():
            for other in actors.values():
                other.SetVisibility(other is actor)
            if before and name in before:
                before[name]()
            plotter.renderer.Modified()
            start = time.perf_counter()
            window.Render()
            if timed:
                times[name].append(time.perf_counter() - start)
    return {name: 1000 * statistics.median(spent) for name, spent in times.items()}


def ball_pixels(plotter, radii: np.ndarray) -> float:
    """The balls' mean diameter on screen (pixels) in plotter's fitted view."""
    camera = plotter.renderer.GetActiveCamera()
    distance = camera.GetDistance()
    height = plotter.window_size[1]
    view_height = 2 * distance * np.tan(np.radians(camera.GetViewAngle() / 2))
    return float(2 * radii.mean() * height / view_height)


def protein(copies: int, probe: float = PROBE) -> dict:
    """bench_molecule's rotated copies of 1A8O: centres (n, 3), van der Waals radii (n,),
    and the window's balls (radii vdW + probe) with their exposed flags (n,) bool."""
    import tempfile

    from bench_molecule import write_copies

    from core.complex import AlphaComplex
    from core.io.molecule import read_molecule
    from core.molecule.analysis import measure_molecule
    from core.molecule.measures import exposed_balls

    with tempfile.TemporaryDirectory(prefix="alphascoop-balls-") as folder:
        path = Path(folder) / "copies.pdb"
        write_copies(copies, path)
        molecule = read_molecule(path)
    ac = AlphaComplex.from_points(molecule.centres, weights=molecule.weights(probe))
    radii = np.sqrt(ac.weights)
    measures = measure_molecule(ac, probe)
    return {"centres": molecule.centres, "vdw": molecule.vdw_radii, "points": ac.points,
            "radii": radii, "exposed": exposed_balls(measures.point_area, radii)}


def seen_actor(plotter, balls, colour: str = COLOUR):
    """A ball actor drawing the balls of the ball mesh `balls` that plotter's view shows, as
    the window does (app.scene.seen_balls), and its SeenBalls."""
    from app.scene.layers import ball_actor
    from app.scene.seen_balls import SeenBalls

    actor = ball_actor(balls, colour, 1.0)
    actor.GetMapper().SetInputData(balls)
    plotter.add_actor(actor, reset_camera=False, render=False)
    seen = SeenBalls(plotter.render_window, plotter.renderer)
    seen.track(actor, balls)
    return actor, seen


def run(copies: int, size: tuple[int, int]) -> dict:
    """Milliseconds per render of each way on the same balls."""
    import pyvista as pv

    from app.scene.layers import ball_actor, ball_mesh, outer_balls

    mol = protein(copies)
    points, radii = mol["points"], mol["radii"]
    plotter = pv.Plotter(off_screen=True, window_size=list(size))
    plotter.render_window.SetMultiSamples(0)  # as the window draws (app.scene.interactive)
    plotter.renderer.SetUseFXAA(True)
    mesh = ball_mesh(points, radii, limit=len(points), exposed=mol["exposed"])
    every = ball_actor(mesh, COLOUR, 1.0)
    plotter.add_actor(every, reset_camera=True, render=False)
    outer_mesh = outer_balls(mesh)
    outer = ball_actor(mesh, COLOUR, 1.0)
    outer.GetMapper().SetInputData(outer_mesh)
    before = ball_actor(mesh, COLOUR, 1.0)
    before.GetShaderProperty().ClearAllShaderReplacements()
    for actor in (outer, before):
        plotter.add_actor(actor, reset_camera=False, render=False)
    balls, seen = seen_actor(plotter, outer_mesh)
    new_view, fresh = seen_actor(plotter, outer_balls(mesh))
    vdw, vdw_seen = seen_actor(plotter, ball_mesh(mol["centres"], mol["vdw"],
                                                  limit=len(points)))
    cloud = pv.PolyData(points)
    plain = plotter.add_mesh(cloud, color="#c9d1d9", point_size=3.0, style="points",
                             render=False, reset_camera=False)
    pixels = ball_pixels(plotter, radii)
    wide = plotter.add_mesh(cloud.copy(), color="#c9d1d9", point_size=pixels, style="points",
                            render=False, reset_camera=False)
    cloud["radius"] = radii
    sphere = pv.Sphere(radius=1.0, theta_resolution=10, phi_resolution=10)
    glyphs = plotter.add_mesh(cloud.glyph(scale="radius", geom=sphere, orient=False),
                              color=COLOUR, render=False, reset_camera=False)
    actors = {"balls": balls, "new_view": new_view, "outer": outer, "every_ball": every,
              "before": before, "vdw": vdw, "plain_points": plain,
              "same_pixel_points": wide, "glyphs": glyphs}

    def forget_view() -> None:
        """The new-view way finds its balls again at its next render (a moved camera)."""
        fresh.forget_view()

    result = {"atoms": len(mol["centres"]), "balls_n": len(points),
              "drawn": int(mol["exposed"].sum()), "size": size,
              "ball_pixels": pixels, "probe": PROBE}
    result.update(render_ms(plotter, actors, {"new_view": forget_view}))
    result["seen"] = balls.GetMapper().GetInput().GetNumberOfPoints() - 2  # - the corners
    result["vdw_seen"] = vdw.GetMapper().GetInput().GetNumberOfPoints() - 2
    plotter.renderer.SetUseFXAA(False)
    for actor in actors.values():
        actor.SetVisibility(False)
    plain_fxaa = render_ms(plotter, {"balls": balls, "plain_points": plain})
    result["balls_no_fxaa"] = plain_fxaa["balls"]
    result["plain_points_no_fxaa"] = plain_fxaa["plain_points"]
    for each in (seen, fresh, vdw_seen):
        each.close()
    plotter.close()
    return result


def figures(result: dict) -> list:
    """The balls against plain points (the goal), against what was drawn before, and the
    parts of the gain."""
    from results import Figure

    n = f"{result['balls_n']:,}"
    label = (f"{n} balls as the window draws them, a still view ({result['seen']:,} it shows "
             f"of {result['drawn']:,} seen from outside), one render")
    points = f"{n} plain points (3 px)"
    return [
        Figure("balls.impostors_vs_points", label, result["balls"], "ms",
               points, result["plain_points"], "<= 2"),
        Figure("balls.new_view_vs_points", f"{n} balls, a new view's id pass and its frame "
               "of the balls it shows (the window paints the new view with every outer ball "
               "first)", result["new_view"], "ms", points, result["plain_points"]),
        Figure("balls.outer_vs_points", f"{n} balls, the {result['drawn']:,} seen from "
               "outside all drawn (before the id pass)", result["outer"], "ms", points,
               result["plain_points"]),
        Figure("balls.every_ball_vs_points", f"{n} balls, all drawn (clipped or translucent)",
               result["every_ball"], "ms", points, result["plain_points"]),
        Figure("balls.before_vs_impostors", f"{n} balls as first drawn (all, light kit)",
               result["before"], "ms", "as the window draws them", result["balls"]),
        Figure("balls.vdw_vs_points", f"{n} balls at van der Waals radii as the window draws "
               f"them, a still view ({result['vdw_seen']:,} it shows)", result["vdw"], "ms",
               points, result["plain_points"]),
        Figure("balls.outer_vs_same_pixels", f"{n} balls, the {result['drawn']:,} seen from "
               "outside all drawn", result["outer"], "ms",
               f"{n} square points {result['ball_pixels']:.0f} px wide (every ball's fill)",
               result["same_pixel_points"]),
        Figure("balls.impostors_vs_points_no_fxaa", label + ", without FXAA",
               result["balls_no_fxaa"], "ms", points + ", without FXAA",
               result["plain_points_no_fxaa"]),
        Figure("balls.glyphs_vs_impostors", f"{n} tessellated sphere glyphs, one render",
               result["glyphs"], "ms", "as the window draws them", result["balls"]),
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
    for name in ("balls", "new_view", "outer", "every_ball", "before", "vdw", "plain_points",
                 "same_pixel_points", "glyphs", "balls_no_fxaa", "plain_points_no_fxaa"):
        print(f"{name:20s} {result[name]:9.1f} ms")
    print(f"balls {result['balls_n']:,} ({result['drawn']:,} exposed, {result['seen']:,} "
          f"shown), {result['ball_pixels']:.1f} px wide on screen")
    if not args.no_save:
        save("balls", figures(result), notes=[
            f"A synthetic protein of {result['atoms']:,} atoms (rotated copies of 1A8O; "
            f"{result['balls_n']:,} balls in its complex, the others inside their "
            f"neighbours') at van der Waals radii + the {PROBE:g} Å probe (the window's balls), "
            f"fitted in a {size[0]} x {size[1]} view, software GL (llvmpipe), one sample a "
            "pixel and FXAA as the window draws; median of "
            f"{RENDERS} full renders each, taken in turns.",
            "On a software renderer the fill is the cost: every covered fragment of every "
            "overlapping ball is shaded (the depth of an impostor is its own, so no early "
            "depth test skips it). The window shades balls with one light at the eye, leaves "
            "out balls inside the union of the others (exact per-atom areas at the drawn "
            "radii) while they are opaque and uncut, and of the rest draws only those the "
            "view shows: an id pass (every outer ball flat in a colour of its own, read back) "
            "finds them once per view, and a still view (a slider step) draws those alone. "
            "The same picture, pixel for pixel (tests/test_app_seen_balls.py)."])


if __name__ == "__main__":
    main()

"""A still view draws only the balls it shows (app.scene.seen_balls): the same picture as
every ball drawn, on random views, and the balls kept are those a ray cast through every
pixel's centre finds in front."""

from __future__ import annotations

import numpy as np
import pytest

from app.palette import LayerStyle, default_styles
from app.scene import Scene, SceneData

pytestmark = pytest.mark.gui
SIZE = (240, 180)


def packed_balls(count: int, seed: int) -> tuple[np.ndarray, np.ndarray]:
    """(count, 3) centres in a box and (count,) radii of 1 to 2.5: balls overlapping so that
    most of them are behind others from any side."""
    rng = np.random.default_rng(seed)
    return rng.uniform(0.0, 20.0, (count, 3)), rng.uniform(1.0, 2.5, count)


@pytest.fixture
def scene():
    """An off-screen scene drawing as the window does (FXAA, one sample a pixel), closed
    afterwards."""
    made = Scene.off_screen(SIZE)
    made.plotter.render_window.SetMultiSamples(0)
    made.plotter.renderer.SetUseFXAA(True)
    yield made
    made.close()


def ball_scene(scene: Scene, centres: np.ndarray, radii: np.ndarray) -> None:
    """The balls alone, opaque, in the scene."""
    styles = {name: LayerStyle(False, style.colour, style.opacity)
              for name, style in default_styles(3).items()}
    styles["balls"] = LayerStyle(True, "#8fb8de", 1.0)
    scene.set_dataset(SceneData(centres, 3, np.zeros((0, 2), np.int64), styles, radii=radii))


def random_view(scene: Scene, rng: np.random.Generator) -> None:
    """Look at the balls from a random direction and distance, in perspective or parallel."""
    camera = scene.plotter.renderer.GetActiveCamera()
    scene.view_preset("iso")
    camera.Azimuth(rng.uniform(0, 360))
    camera.Elevation(rng.uniform(-80, 80))
    camera.OrthogonalizeViewUp()
    camera.SetParallelProjection(bool(rng.random() < 0.3))
    camera.Dolly(rng.uniform(0.8, 2.5))
    scene.plotter.renderer.ResetCameraClippingRange()


def drawn(scene: Scene):
    """The ball mesh the balls' mapper draws now."""
    return scene.layers["balls"].actor.GetMapper().GetInput()


def picture(scene: Scene) -> np.ndarray:
    """The frame drawn now."""
    scene.plotter.render()
    return scene.plotter.screenshot(None).copy()


def test_a_still_view_draws_fewer_balls_and_the_same_picture(scene) -> None:
    """On random views (perspective and parallel), each found anew when the camera moves,
    the balls drawn are a few of them and the frame is the one every ball gives, pixel for
    pixel."""
    from vtkmodules.vtkRenderingCore import vtkCamera

    centres, radii = packed_balls(1500, seed=3)
    ball_scene(scene, centres, radii)
    layer = scene.layers["balls"]
    camera = scene.plotter.renderer.GetActiveCamera()
    scene.seen.track(layer.actor, None)  # every ball drawn: the pictures to match
    rng = np.random.default_rng(11)
    views, pictures = [], []
    for _ in range(5):
        random_view(scene, rng)
        pictures.append(picture(scene))
        views.append(vtkCamera())
        views[-1].DeepCopy(camera)
    assert drawn(scene) is layer.mesh
    scene.seen.track(layer.actor, layer.mesh)
    counts = []
    for view, every in zip(views, pictures, strict=True):
        camera.DeepCopy(view)
        shown = picture(scene)
        counts.append(drawn(scene).GetNumberOfPoints())
        assert 0 < counts[-1] < 0.5 * len(centres)
        assert shown.std() > 10
        np.testing.assert_array_equal(shown, every)
    assert len(set(counts)) > 1  # each view its own balls


def test_a_moving_view_draws_every_ball_until_it_stops(scene) -> None:
    """While an interaction moves the view (a drag), every ball is drawn; once it ends,
    the balls of the new view, with the same picture."""
    centres, radii = packed_balls(600, seed=9)
    ball_scene(scene, centres, radii)
    layer = scene.layers["balls"]
    picture(scene)
    assert drawn(scene).GetNumberOfPoints() < len(centres)
    style = scene.plotter.iren.interactor.GetInteractorStyle()
    style.StartRotate()  # what a press of the left button starts
    scene.plotter.renderer.GetActiveCamera().Azimuth(50.0)
    moving = picture(scene)
    assert drawn(scene) is layer.mesh
    style.EndRotate()
    np.testing.assert_array_equal(picture(scene), moving)
    assert drawn(scene).GetNumberOfPoints() < len(centres)


def test_translucent_clipped_or_multisampled_balls_are_all_drawn(scene) -> None:
    """Inner balls show through translucent or clipped ones; a multisampled frame has
    samples off the pixels' centres the id pass looks at: every ball is drawn then."""
    centres, radii = packed_balls(400, seed=5)
    ball_scene(scene, centres, radii)
    every = len(centres) + 2  # + the box's two corners
    picture(scene)
    assert drawn(scene).GetNumberOfPoints() < every
    scene.set_style("balls", LayerStyle(True, "#8fb8de", 0.5))
    picture(scene)
    assert drawn(scene).GetNumberOfPoints() == every
    scene.set_style("balls", LayerStyle(True, "#8fb8de", 1.0))
    scene.set_clipping(True)
    picture(scene)
    assert drawn(scene).GetNumberOfPoints() == every
    scene.set_clipping(False)
    picture(scene)
    assert drawn(scene).GetNumberOfPoints() < every
    scene.plotter.render_window.SetMultiSamples(4)
    picture(scene)
    assert drawn(scene).GetNumberOfPoints() == every


def pixel_rays(scene: Scene) -> tuple[np.ndarray, np.ndarray]:
    """(p, 3) origins and unit directions of the rays through every pixel's centre of the
    scene's view (from the camera's world-to-screen matrix)."""
    renderer = scene.plotter.renderer
    width, height = renderer.GetSize()
    matrix = renderer.GetActiveCamera().GetCompositeProjectionTransformMatrix(
        renderer.GetTiledAspectRatio(), -1, 1)
    to_world = np.linalg.inv(np.array([[matrix.GetElement(i, j) for j in range(4)]
                                       for i in range(4)]))
    cols, rows = np.meshgrid(np.arange(width), np.arange(height))
    x = 2 * (cols.ravel() + 0.5) / width - 1
    y = 2 * (rows.ravel() + 0.5) / height - 1
    ends = []
    for z in (-1.0, 1.0):
        ndc = np.stack([x, y, np.full_like(x, z), np.ones_like(x)], axis=1)
        world = ndc @ to_world.T
        ends.append(world[:, :3] / world[:, 3:])
    direction = ends[1] - ends[0]
    return ends[0], direction / np.linalg.norm(direction, axis=1)[:, None]


def ray_cast(origins: np.ndarray, directions: np.ndarray, centres: np.ndarray,
             radius: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Brute force along (p, 3) rays through (b,) balls: (b,) bool `in_front`, the balls
    nearest along some ray clearly (the ray not at their rim, the next hit more than a hair
    behind), and (b,) bool `reachable`, the balls some ray hits or grazes no further than a
    hair behind the nearest hit along it."""
    hair = 1e-3 * radius.max()
    in_front = np.zeros(len(radius), bool)
    reachable = radius == 0
    for start in range(0, len(origins), 2000):
        o, d = origins[start:start + 2000], directions[start:start + 2000]
        offset = centres[None, :, :] - o[:, None, :]  # (rays, balls, 3)
        along = np.einsum("pbk,pk->pb", offset, d)
        miss2 = np.einsum("pbk,pbk->pb", offset, offset) - along ** 2  # squared ray distance
        inside = radius[None, :] ** 2 - miss2
        hit = inside > 0
        depth = np.where(hit, along - np.sqrt(np.where(hit, inside, 0.0)), np.inf)
        order = np.argsort(depth, axis=1)[:, :2]
        rows = np.arange(len(depth))
        first = order[:, 0]
        best, next_best = depth[rows, first], depth[rows, order[:, 1]]
        gap = np.subtract(next_best, best, out=np.zeros_like(best), where=np.isfinite(best))
        clear = (np.isfinite(best) & (gap > hair)
                 & (miss2[rows, first] < (radius[first] * (1 - 1e-3)) ** 2))
        in_front[first[clear]] = True
        grazed = (miss2 < (radius[None, :] * (1 + 1e-3)) ** 2) & (along <= best[:, None] + hair)
        reachable |= (hit & (depth <= best[:, None] + hair) | grazed).any(axis=0)
    return in_front, reachable


def test_the_balls_kept_are_those_in_front_at_some_pixel(scene) -> None:
    """A brute-force ray cast through every pixel's centre: each ball nearest along some
    ray (clearly: not at a rim, not tied with another) is kept, and each ball kept is hit
    by some ray no further than a hair behind the nearest hit there."""
    centres, radii = packed_balls(300, seed=7)
    ball_scene(scene, centres, radii)
    rng = np.random.default_rng(2)
    mesh = scene.layers["balls"].mesh
    world = np.asarray(mesh.points, np.float64) + np.asarray(mesh.field_data["origin"])
    radius = np.asarray(mesh["radius"], np.float64)
    for _ in range(3):
        random_view(scene, rng)
        picture(scene)
        kept = set(map(tuple, np.asarray(drawn(scene).points)))
        kept_rows = np.array([tuple(p) in kept for p in np.asarray(mesh.points)])
        in_front, reachable = ray_cast(*pixel_rays(scene), world, radius)
        assert in_front.sum() > 20
        assert kept_rows[in_front].all()  # none left out that shows
        assert reachable[kept_rows].all()  # none kept that no pixel shows


def test_without_an_id_pass_every_ball_is_drawn(scene, monkeypatch) -> None:
    """Where the id pass cannot draw (no OpenGL context for it), every ball is drawn."""
    from app.scene.seen_balls import IdPass

    made = IdPass.__init__

    def unusable(self) -> None:
        made(self)
        self.usable = False

    monkeypatch.setattr(IdPass, "__init__", unusable)
    centres, radii = packed_balls(300, seed=4)
    ball_scene(scene, centres, radii)
    picture(scene)
    assert drawn(scene) is scene.layers["balls"].mesh


def test_a_deferred_id_pass_runs_after_the_frame_of_a_new_view() -> None:
    """As in the window (its event loop runs the pass once the frame is painted): a new
    view's frame draws every ball, the pass then finds those it shows, and the next frame
    draws those with the same picture; a view that moved again meanwhile is the one found."""
    tasks = []
    scene = Scene.off_screen(SIZE)
    scene.seen.defer = tasks.append  # what interactive_scene gives: a call after the frame
    try:
        scene.plotter.render_window.SetMultiSamples(0)
        centres, radii = packed_balls(800, seed=6)
        ball_scene(scene, centres, radii)
        layer = scene.layers["balls"]
        first = picture(scene)
        assert drawn(scene) is layer.mesh and len(tasks) == 1
        picture(scene)
        assert len(tasks) == 1  # one pass waiting, not one a frame
        tasks.pop()()
        assert drawn(scene).GetNumberOfPoints() < 0.5 * len(centres)
        np.testing.assert_array_equal(picture(scene), first)
        assert not tasks  # the view is known
        camera = scene.plotter.renderer.GetActiveCamera()
        camera.Azimuth(40.0)
        moved = picture(scene)
        assert drawn(scene) is layer.mesh and len(tasks) == 1
        camera.Elevation(30.0)
        camera.OrthogonalizeViewUp()
        again = picture(scene)
        tasks.pop()()
        shown = drawn(scene).GetNumberOfPoints()
        np.testing.assert_array_equal(picture(scene), again)
        assert drawn(scene).GetNumberOfPoints() == shown < 0.5 * len(centres)
        assert not np.array_equal(moved, again)
    finally:
        scene.close()


def every_ball_picture(scene: Scene) -> np.ndarray:
    """The frame with every ball drawn (culling off for it, then on again: the balls are
    found anew after it)."""
    layer = scene.layers["balls"]
    scene.seen.track(layer.actor, None)
    layer.actor.GetMapper().SetInputData(layer.mesh)
    every = picture(scene)
    scene.seen.track(layer.actor, layer.mesh)
    return every


def test_a_resized_window_or_a_second_dataset_finds_its_balls_anew(scene) -> None:
    """The balls found for a view are not kept past it: a window resized at the same aspect
    (the same camera matrix, more pixels) or new balls in the scene draw the balls found
    for them, with the picture every ball gives."""
    centres, radii = packed_balls(800, seed=12)
    ball_scene(scene, centres, radii)
    picture(scene)
    small = drawn(scene)
    assert small.GetNumberOfPoints() < len(centres)
    scene.plotter.window_size = [2 * SIZE[0], 2 * SIZE[1]]
    shown = picture(scene)
    assert drawn(scene) is not small and drawn(scene).GetNumberOfPoints() < len(centres)
    np.testing.assert_array_equal(shown, every_ball_picture(scene))
    others, other_radii = packed_balls(800, seed=13)
    ball_scene(scene, others + 5.0, other_radii)
    shown = picture(scene)
    new = set(map(tuple, np.asarray(scene.layers["balls"].mesh.points).tolist()))
    assert set(map(tuple, np.asarray(drawn(scene).points).tolist())) <= new
    assert drawn(scene).GetNumberOfPoints() < len(others)
    np.testing.assert_array_equal(shown, every_ball_picture(scene))

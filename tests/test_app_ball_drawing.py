"""How the scene draws balls: only those seen from outside while opaque and uncut (checked
against freesasa's per-atom areas and by the picture itself), each lit from the eye at its
own radius in data units."""

from __future__ import annotations

import numpy as np
import pytest

from app.dataset import load_dataset
from app.palette import ATOM_STYLE, LayerStyle, cpk_rgb, default_styles
from app.scene import Scene, SceneData, scene_data
from tests.molecule_reference import freesasa_area, shared_molecule
from tests.reference import DATA_ABSENT

PDB = shared_molecule("1A8O.pdb")
pytestmark = pytest.mark.gui
SIZE = (480, 360)
molecule_data = pytest.mark.skipif(PDB is None, reason=DATA_ABSENT)


@pytest.fixture
def scene():
    """An off-screen scene, closed afterwards."""
    made = Scene.off_screen(SIZE)
    yield made
    made.close()


@pytest.fixture(scope="module")
def molecule():
    """1A8O opened as the window opens it (its measures at alpha² 0)."""
    return load_dataset(PDB, lambda *_: None, topology=False)


def molecule_scene(scene: Scene, dataset) -> None:
    """The molecule's atoms drawn as the window draws them (CPK colours, opaque), alone."""
    styles = {name: LayerStyle(False, style.colour, style.opacity)
              for name, style in default_styles(3).items()}
    styles["balls"] = ATOM_STYLE
    scene.set_dataset(scene_data(dataset, styles, cpk_rgb(dataset.atomic_numbers)))


def picture(scene: Scene) -> np.ndarray:
    """The frame drawn now (a screenshot alone gives the last frame drawn, which may be
    older than the mapper's input)."""
    scene.plotter.render()
    return scene.plotter.screenshot(None).copy()


def drawn(scene: Scene):
    """The ball mesh the balls' mapper draws now."""
    return scene.layers["balls"].actor.GetMapper().GetInput()


@molecule_data
def test_left_out_balls_have_no_exposed_area_by_freesasa(molecule) -> None:
    """The balls left out are exactly those freesasa finds no area on, at the radii drawn
    (the union of the atoms' balls, probe 0 on radii van der Waals + 1.4 Å)."""
    ac = molecule.ac
    data = scene_data(molecule, {**default_styles(3), "balls": ATOM_STYLE})
    radii = np.sqrt(ac.weights)
    np.testing.assert_allclose(data.radii, radii)
    _, area = freesasa_area(ac.points, radii, slices=200)
    exposed, ours = data.exposed, molecule.molecule.point_area
    assert 0 < (~exposed).sum() < len(exposed) // 2  # buried atoms exist, most are not
    assert (area[~exposed] == 0).all()  # none left out that freesasa sees
    assert (ours[~exposed] > 0).any()  # the sum's rounding left some buried balls an area
    # freesasa's slices (0.03 Å apart here) miss slivers narrower than that, nothing more
    missed = exposed & (area == 0)
    assert missed.sum() <= 2 and (ours[missed] < 0.01).all()


@molecule_data
def test_outer_balls_draw_the_same_picture(scene, molecule) -> None:
    """Opaque and uncut, the balls inside the union are not drawn and the picture is the
    same pixel for pixel; clipped or translucent, every ball is drawn again."""
    molecule_scene(scene, molecule)
    layer = scene.layers["balls"]
    exposed = scene_data(molecule, {**default_styles(3), "balls": ATOM_STYLE}).exposed
    assert drawn(scene).GetNumberOfPoints() == exposed.sum() + 2  # + the box's two corners
    assert layer.mesh.n_points == len(exposed) + 2
    outer = picture(scene)
    assert outer.std() > 10  # a picture, not a blank frame
    layer.actor.GetMapper().SetInputData(layer.mesh)
    np.testing.assert_array_equal(outer, picture(scene))
    scene.set_style("balls", ATOM_STYLE)
    assert drawn(scene) is layer.outer
    scene.set_style("balls", LayerStyle(True, ATOM_STYLE.colour, 0.5))
    assert drawn(scene) is layer.mesh
    scene.set_style("balls", ATOM_STYLE)
    scene.set_clipping(True)
    assert drawn(scene) is layer.mesh
    scene.set_clipping(False)
    assert drawn(scene) is layer.outer


def test_a_ball_is_lit_from_the_eye_at_its_radius(scene) -> None:
    """One ball seen head on: brightest at its centre (lit from the eye, so its shading
    follows the view), darker towards its rim, and as wide on screen as its radius in data
    units."""
    radius = 2.0
    styles = {name: LayerStyle(False, style.colour, style.opacity)
              for name, style in default_styles(3).items()}
    styles["balls"] = LayerStyle(True, "#ffffff", 1.0)
    xyz = np.array([[0.0, 0.0, 0.0], [10.0, 10.0, 10.0]])
    scene.set_dataset(SceneData(xyz, 3, np.zeros((0, 2), np.int64), styles,
                                radii=np.array([radius, 0.0])))
    camera = scene.plotter.renderer.GetActiveCamera()
    camera.SetFocalPoint(0.0, 0.0, 0.0)
    camera.SetPosition(0.0, 0.0, 50.0)
    camera.SetViewUp(0.0, 1.0, 0.0)
    camera.SetViewAngle(30.0)
    scene.plotter.renderer.ResetCameraClippingRange()
    half = 80  # the middle of the view: the legend and scale bar stay out
    rows, cols = SIZE[1] // 2 - half, SIZE[0] // 2 - half
    image = scene.plotter.screenshot(None).astype(float).sum(axis=2)
    image = image[rows:rows + 2 * half, cols:cols + 2 * half]
    background = image[0, 0]
    ball = np.abs(image - background) > 1
    ys, xs = np.nonzero(ball)
    centre = np.array([(SIZE[1] - 1) / 2 - rows, (SIZE[0] - 1) / 2 - cols])
    np.testing.assert_allclose([ys.mean(), xs.mean()], centre, atol=1.0)
    # the silhouette's half-width: the radius seen from 50 units away through a 30° view
    seen = radius / np.sqrt(50.0 ** 2 - radius ** 2)
    expected = seen / np.tan(np.radians(15.0)) * SIZE[1] / 2
    assert (xs.max() - xs.min() + 1) / 2 == pytest.approx(expected, abs=1.5)
    brightest = np.unravel_index(np.argmax(np.where(ball, image, -1)), image.shape)
    assert np.hypot(*(np.array(brightest) - centre)) < 2.0
    ring = ball & (np.hypot(*(np.indices(image.shape) - centre[:, None, None])) > 0.8 * expected)
    assert image[ring].mean() < 0.7 * image[brightest]


@molecule_data
def test_exposed_balls_known_after_the_first_frame(scene, molecule) -> None:
    """A molecule drawn before its measures arrive shows every ball; told its exposed balls
    later, the scene draws only those, and the picture stays the same."""
    from dataclasses import replace

    molecule_scene(scene, replace(molecule, molecule=None))
    layer = scene.layers["balls"]
    assert drawn(scene) is layer.mesh and layer.outer is None
    every = picture(scene)
    exposed = scene_data(molecule, {**default_styles(3), "balls": ATOM_STYLE}).exposed
    scene.set_exposed(exposed)
    assert drawn(scene) is layer.outer
    assert drawn(scene).GetNumberOfPoints() == exposed.sum() + 2
    np.testing.assert_array_equal(picture(scene), every)



def test_a_thinned_ball_set_draws_its_buried_balls(scene, monkeypatch) -> None:
    """Balls thinned to at most a limit (a big molecule) are not the union the exposed areas
    were measured on: a buried ball whose cover is partly left out shows, so it is drawn."""
    import functools

    import app.scene.view
    from app.scene.layers import ball_mesh

    axes = np.concatenate([np.eye(3), -np.eye(3)])
    xyz = np.concatenate([np.zeros((1, 3)), axes])  # a ball and the six that cover it
    radii = np.array([1.0] + [1.5] * 6)
    sphere = np.random.default_rng(7).normal(size=(2000, 3))
    sphere /= np.linalg.norm(sphere, axis=1, keepdims=True)
    cover = np.linalg.norm(sphere[:, None] - axes[None], axis=2) < 1.5
    assert cover.any(axis=1).all()  # the first ball is buried in the others
    monkeypatch.setattr(app.scene.view, "ball_mesh", functools.partial(ball_mesh, limit=2))
    styles = {name: LayerStyle(False, style.colour, style.opacity)
              for name, style in default_styles(3).items()}
    styles["balls"] = LayerStyle(True, "#ffffff", 1.0)
    scene.set_dataset(SceneData(xyz, 3, np.zeros((0, 2), np.int64), styles, radii=radii,
                                exposed=np.arange(7) > 0))
    layer = scene.layers["balls"]
    assert layer.mesh.n_points == 2 + 2  # the buried ball and one of its cover, and corners
    shown = picture(scene)
    layer.actor.GetMapper().SetInputData(layer.mesh)
    np.testing.assert_array_equal(shown, picture(scene))


@molecule_data
def test_a_still_view_draws_only_the_outer_balls_it_shows(scene, molecule) -> None:
    """Drawn as the window draws (one sample a pixel, FXAA), a still view draws only the
    outer balls it shows (app.scene.seen_balls), a few of them, with the same picture as
    every ball drawn, from several sides."""
    scene.plotter.render_window.SetMultiSamples(0)
    scene.plotter.renderer.SetUseFXAA(True)
    molecule_scene(scene, molecule)
    layer = scene.layers["balls"]
    camera = scene.plotter.renderer.GetActiveCamera()
    for turn in (0.0, 70.0, 150.0):
        camera.Azimuth(turn)
        camera.Elevation(turn / 5)
        camera.OrthogonalizeViewUp()
        scene.plotter.renderer.ResetCameraClippingRange()
        shown = picture(scene)
        assert drawn(scene).GetNumberOfPoints() < 0.6 * layer.outer.n_points
        scene.seen.track(layer.actor, None)
        layer.actor.GetMapper().SetInputData(layer.mesh)
        np.testing.assert_array_equal(shown, picture(scene))
        scene.seen.track(layer.actor, layer.outer)

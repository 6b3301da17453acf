"""The window on weighted points: it builds the weighted complex, shows alpha² (negative too)
on the slider's field, the info dock and the status line, draws the balls layer (capped),
plots signatures on a symmetric-log axis, and exports at negative alpha²."""

from __future__ import annotations

import numpy as np
import pytest
from conftest import open_and_wait

from app.palette import MAX_BALLS
from app.scene import ball_mesh


@pytest.fixture
def balls_csv(tmp_path):
    """A weighted CSV (x, y, z, radius): 800 balls of radius 0.02-0.06 in the unit cube."""
    rng = np.random.default_rng(5)
    table = np.column_stack([rng.random((800, 3)), rng.uniform(0.02, 0.06, 800)])
    path = tmp_path / "balls.csv"
    np.savetxt(path, table, delimiter=",", header="x,y,z,radius", comments="")
    return path, table


def test_weighted_csv_opens_with_alpha2_everywhere(window, qtbot, balls_csv) -> None:
    path, table = balls_csv
    open_and_wait(qtbot, window, path)
    model = window.model
    ac = model.dataset.ac
    assert model.weighted and ac.weights is not None
    shown = np.flatnonzero(ac.input_index >= 0)
    np.testing.assert_allclose(ac.weights[ac.input_index[shown]], table[shown, 3] ** 2)
    model.set_index(0)  # the lowest critical value: a squared radius below zero
    assert model.alpha2 < 0
    assert model.shape.alpha2 == pytest.approx(model.alpha2)
    assert window.alpha_panel.squared.text() == f"{model.alpha2:.6g}"
    assert window.alpha_panel.radius.text() == ""
    assert "alpha²" in window.info_panel.shape.text()
    assert "hidden point" in window.info_panel.data.text()
    assert "alpha²" in window.status.text()


def test_balls_layer_draws_each_point_with_its_radius(window, qtbot, balls_csv) -> None:
    open_and_wait(qtbot, window, balls_csv[0])
    assert "balls" in window.scene.layers and "balls" in window.layers_panel.rows
    assert "20,000" in window.layers_panel.rows["balls"].visible.text()
    layer = window.scene.layers["balls"]
    ac = window.model.dataset.ac
    bounds = np.array(layer.actor.GetBounds()).reshape(3, 2)  # where the view puts them
    lo = (ac.points - np.sqrt(ac.weights)[:, None]).min(axis=0)
    hi = (ac.points + np.sqrt(ac.weights)[:, None]).max(axis=0)
    np.testing.assert_allclose(bounds[:, 0], lo, atol=1e-6)  # float32 offsets from an origin
    np.testing.assert_allclose(bounds[:, 1], hi, atol=1e-6)
    drawn = layer.mesh["radius"] > 0  # one sphere impostor per ball, at its own radius
    origin = layer.mesh.field_data["origin"]
    np.testing.assert_allclose(layer.mesh.points[drawn] + origin, ac.points, atol=1e-6)
    np.testing.assert_allclose(layer.mesh["radius"][drawn], np.sqrt(ac.weights), rtol=1e-6)
    assert (bounds[:, 0] < ac.points.min(axis=0) - 0.01).all()  # the balls, not the points
    actors = set(window.scene.plotter.renderer.actors)
    window.model.set_index(window.model.index + 1)  # a static layer: no new actor
    assert set(window.scene.plotter.renderer.actors) == actors


def test_ball_count_is_capped() -> None:
    xyz = np.random.default_rng(1).random((MAX_BALLS + 500, 3))
    mesh = ball_mesh(xyz, np.full(len(xyz), 0.01), limit=50)
    assert int((mesh["radius"] > 0).sum()) == 50


def test_signature_axes_are_symlog_and_the_cursor_reaches_negatives(window, qtbot,
                                                                     balls_csv) -> None:
    open_and_wait(qtbot, window, balls_csv[0])
    axes = window.signatures_panel.figure.axes
    assert axes and all(ax.get_xscale() == "symlog" for ax in axes)
    assert min(ax.get_xlim()[0] for ax in axes) < 0
    window.model.set_index(0)
    assert window.signatures_panel.cursors[0].get_xdata()[0] == pytest.approx(window.model.alpha2)


def test_export_at_a_negative_alpha2(window, qtbot, balls_csv, tmp_path) -> None:
    from app import file_actions

    open_and_wait(qtbot, window, balls_csv[0])
    window.model.set_index(5)
    model = window.model
    assert model.alpha2 < 0
    line = file_actions.write_shape_file(model.dataset.ac, model.alpha, tmp_path / "low.vtu")
    assert f"alpha² {model.alpha2:.6g}" in line
    assert (tmp_path / "low.vtu").is_file()


def test_signed_travel_spreads_negative_values_over_the_slider() -> None:
    from app.log_travel import TRAVEL
    from app.signed_travel import SignedTravel

    squares = np.concatenate([-np.geomspace(1e-2, 1e-5, 300), [0.0], np.geomspace(1e-5, 1e2,
                                                                                  700)])
    spectrum = np.sign(squares) * np.sqrt(np.abs(squares))
    travel = SignedTravel(spectrum)
    positions = np.array([travel.position(i) for i in range(len(spectrum))])
    assert positions[0] == 0 and positions[-1] == TRAVEL
    assert (np.diff(positions) >= 0).all()
    assert 0.05 * TRAVEL < positions[300] < 0.95 * TRAVEL  # zero sits inside, not at an end
    assert len(np.unique(positions[:300])) > 100  # the negative values are spread out
    for i in (10, 150, 300, 650, 990):
        assert abs(travel.index_at(positions[i]) - i) <= 3
    assert travel.page(150, up=True) > 150 and travel.page(150, up=False) < 150


def test_weighted_slider_uses_the_signed_travel(window, qtbot, balls_csv) -> None:
    from app.signed_travel import SignedTravel

    open_and_wait(qtbot, window, balls_csv[0])
    panel = window.alpha_panel
    assert isinstance(panel.travel, SignedTravel)
    window.model.set_index(3)
    assert window.model.alpha2 < 0 and panel.slider.value() == panel.travel.position(3)

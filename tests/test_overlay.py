"""Pictures that explain themselves: legend, alpha, scale bar and orientation marker."""

from __future__ import annotations

import numpy as np
import pytest
from conftest import open_and_wait
from PIL import Image

from app.__main__ import main
from app.numbers import coordinate, plural, quantity
from app.palette import BACKGROUND, CLASS_COLOURS, default_styles
from app.scene.overlay import alpha_caption, legend_entries, length_label, round_length

CORNER = (0.16, 0.12)  # the top-left share of the picture where the legend sits


def corner_differs(png) -> float:
    """Share of the top-left corner's pixels that are not the background colour."""
    image = np.asarray(Image.open(png).convert("RGB")).astype(int)
    h, w = image.shape[:2]
    corner = image[: int(h * CORNER[1]), : int(w * CORNER[0])]
    background = np.array([int(BACKGROUND[i:i + 2], 16) for i in (1, 3, 5)])
    return float(np.mean(np.abs(corner - background).sum(axis=2) > 30))


@pytest.mark.parametrize(("target", "length"), [(7.3, 5.0), (0.031, 0.02), (1.0, 1.0),
                                                (19999.0, 10000.0)])
def test_scale_bar_takes_a_round_length(target, length) -> None:
    assert round_length(target) == pytest.approx(length)


def test_legend_gives_one_line_per_colour() -> None:
    """Surface, singular edges and singular points have colours of their own, in 3D as in
    2D, and a line each; painted layers (no swatch) stay apart while colouring by a value;
    counts, where given, follow each title."""
    blue = CLASS_COLOURS["regular"]
    lines_3d = legend_entries(default_styles(3))
    assert [label for label, _ in lines_3d] == ["Surface", "Singular edges", "Singular points"]
    assert len({swatch for _, swatch in lines_3d}) == 3 and lines_3d[0][1] == blue
    lines_2d = legend_entries(default_styles(2))
    assert [label for label, _ in lines_2d] == [
        "Boundary (regular)", "Interior cells", "Singular edges", "Singular points"]
    assert len({swatch for _, swatch in lines_2d}) == 4
    painted = legend_entries(default_styles(3), "intensity",
                             frozenset({"surface", "singular_edges"}))
    assert painted == [("Coloured by intensity", None), ("Surface", None),
                       ("Singular edges", None), ("Singular points", lines_3d[2][1])]
    counted = legend_entries(default_styles(3), counts={"surface": 1200, "singular_points": 3})
    assert [label for label, _ in counted] == ["Surface: 1,200 triangles", "Singular edges",
                                               "Singular points: 3"]


def test_labels_read_as_people_write_them() -> None:
    assert length_label(5e6, "m") == "5,000 km" and length_label(0.05, None) == "0.05"
    assert alpha_caption(0.00110545, None) == "alpha: r 0.001105, r² 1.222e-06"
    assert alpha_caption(2.0, "m") == "alpha: r 2.000 m, r² 4.000 m²"
    assert coordinate(4918340.123, 40.0) == "4918340.123" and quantity(4918339.5) == "4,918,340"
    assert plural(1, "point") == "1 point" and plural(2, "vertex", "vertices") == "2 vertices"


def test_screenshot_has_a_legend_unless_asked_not_to(tmp_path, capsys) -> None:
    """--screenshot draws the legend in the top-left corner; --no-legend leaves it bare."""
    rng = np.random.default_rng(0)
    np.save(tmp_path / "p.npy", rng.normal(size=(400, 3)))
    with_legend, without = tmp_path / "a.png", tmp_path / "b.png"
    source = str(tmp_path / "p.npy")
    assert main([source, "--screenshot", str(with_legend), "--size", "480x320"]) == 0
    assert main([source, "--screenshot", str(without), "--size", "480x320", "--no-legend"]) == 0
    assert corner_differs(with_legend) > 0.05
    assert corner_differs(without) == 0.0


def test_window_screenshot_carries_the_legend_and_alpha(window, qtbot, tmp_path) -> None:
    """File → Save screenshot: the legend lists the visible layers, the alpha text follows the
    slider, and the saved picture has the legend in its corner."""
    from app.file_actions import write_screenshot

    np.save(tmp_path / "p.npy", np.random.default_rng(1).normal(size=(500, 3)))
    open_and_wait(qtbot, window, tmp_path / "p.npy")
    overlay = window.scene.overlay
    assert overlay.alpha.GetInput() == alpha_caption(window.model.alpha, None)
    window.model.set_index(window.model.index + 1)
    assert overlay.alpha.GetInput() == alpha_caption(window.model.alpha, None)
    labels = [overlay.legend.GetEntryString(i) for i in range(overlay.legend.GetNumberOfEntries())]
    assert labels[0].startswith("Surface") and not any("Interior cells" in t for t in labels)
    window.scene.plotter.interactor.update()
    qtbot.wait(50)
    write_screenshot(window.scene, tmp_path / "shot.png")
    assert corner_differs(tmp_path / "shot.png") > 0.05

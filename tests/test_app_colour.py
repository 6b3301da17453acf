"""Colour by: the values on the drawn cells and points are the table's, the component labels
the core's, the attributes the file's; changing the colour never touches the geometry."""

from __future__ import annotations

import numpy as np
import pytest
from conftest import image_contrast, open_and_wait

from app.palette import LAYER_TITLES, default_styles
from app.scene.overlay import merge_same_swatch
from app.scene.painting import SCALARS
from core.query.spheres import find_simplex
from core.topology.components import solid_labels


def scan_like(n: int = 1500, seed: int = 9) -> np.ndarray:
    """(n, 3) two noisy blobs, the second smaller: two solid components at mid alphas."""
    rng = np.random.default_rng(seed)
    return np.concatenate([rng.normal(size=(n - n // 4, 3)),
                           0.4 * rng.normal(size=(n // 4, 3)) + np.array([5.0, 0.0, 0.0])])


@pytest.fixture
def opened(window, qtbot, tmp_path):
    """The window on a CSV with intensity and RGB columns; interior shown."""
    points = scan_like()
    rng = np.random.default_rng(1)
    intensity = rng.uniform(0, 1000, len(points)).round(1)
    rgb = rng.integers(0, 256, (len(points), 3))
    path = tmp_path / "scan.csv"
    rows = [f"{x:.17g},{y:.17g},{z:.17g},{i},{r},{g},{b}"
            for (x, y, z), i, (r, g, b) in zip(points, intensity, rgb, strict=True)]
    path.write_text("x,y,z,intensity,r,g,b\n" + "\n".join(rows) + "\n")
    open_and_wait(qtbot, window, path)
    window.layers_panel._edit("interior", visible=True,
                              opacity=default_styles(3)["interior"].opacity)
    window.file_columns = (points, intensity, rgb)
    return window


def drawn_values(win, name: str) -> np.ndarray:
    """The colour scalars on a layer's cells."""
    return np.asarray(win.scene.meshes[name].cell_data[SCALARS])


def geometry(win) -> dict[str, object]:
    """The drawn connectivity of every layer (objects, to check they are not replaced)."""
    return {name: layer.cells for name, layer in win.scene.layers.items()}


def test_colour_by_enter_alpha_shows_the_tables_values(opened, qtbot) -> None:
    """Every drawn simplex is coloured by its enter alpha from the table; the geometry and the
    shape stay the very same objects; a slider step recolours the new cells."""
    win = opened
    ac = win.model.dataset.ac
    before, shape = geometry(win), win.scene.shape
    win.colourer.set_mode("enter")
    assert geometry(win) == before and win.scene.shape is shape
    for step in range(2):
        for name in ("surface", "interior", "singular_edges"):
            cells = win.scene.layers[name].cells
            values = drawn_values(win, name) if len(cells) else np.zeros(0)
            assert len(values) == len(cells)
            for row in np.linspace(0, len(cells) - 1, 8).astype(int) if len(cells) else []:
                k, found = find_simplex(ac, cells[row])
                assert values[row] == ac.intervals(k)[found, 0]
            assert np.all(values <= win.model.alpha)
        mapper = win.scene.layers["surface"].actor.mapper
        assert mapper.GetScalarVisibility() and mapper.GetLookupTable().GetScale() == 1  # log
        assert mapper.GetScalarRange()[1] == pytest.approx(win.model.alpha)
        if step == 0:
            win.model.set_index(win.model.index - 40)
    assert "enters at alpha (r)" in win.scene.plotter.scalar_bars


def test_colour_by_component_uses_the_cores_labels(opened) -> None:
    """Cells take their solid component; boundary facets that of their cell."""
    win = opened
    ac = win.model.dataset.ac
    sig = ac.signatures()
    two = np.flatnonzero(sig.solid_components == 2)
    win.model.set_alpha(float(sig.alphas[two[len(two) // 2]]))
    win.colourer.set_mode("component")
    labels = solid_labels(ac, win.model.alpha)
    interior = drawn_values(win, "interior")
    np.testing.assert_array_equal(interior, labels[: len(interior)])
    assert set(np.unique(interior).tolist()) == {0.0, 1.0}
    boundary = drawn_values(win, "surface")  # regular triangles, then singular ones
    assert set(np.unique(boundary[np.isfinite(boundary)]).tolist()) == {0.0, 1.0}
    cells = win.scene.layers["surface"].cells
    sides = np.asarray(ac.facet_cells())
    for row in np.linspace(0, len(cells) - 1, 30).astype(int):
        _, facet = find_simplex(ac, cells[row])
        inside = [c for c in sides[facet] if 0 <= c < len(labels)]
        if inside:  # a regular triangle: its cell's component
            assert len(inside) == 1 and boundary[row] == labels[inside[0]]
        else:  # a singular triangle bounds no cell: no component (grey)
            assert np.isnan(boundary[row])


def test_colour_by_point_attributes(opened) -> None:
    """Intensity and RGB from the file land on the right points (via input_index)."""
    win = opened
    ac = win.model.dataset.ac
    _, intensity, rgb = win.file_columns
    keys = [mode.key for mode in win.colourer.modes]
    assert {"attribute:intensity", "attribute:colors"} <= set(keys)
    win.colourer.set_mode("attribute:intensity")
    mesh = win.scene.meshes["surface"]
    np.testing.assert_allclose(np.asarray(mesh.point_data[SCALARS])[ac.input_index], intensity)
    assert win.scene.layers["surface"].actor.mapper.GetScalarVisibility()
    assert "Intensity" in win.scene.plotter.scalar_bars
    win.colourer.set_mode("attribute:colors")
    np.testing.assert_array_equal(np.asarray(mesh.point_data[SCALARS])[ac.input_index], rgb)
    assert win.scene.plotter.scalar_bars == {} or "Intensity" not in win.scene.plotter.scalar_bars


def test_menu_lists_the_modes_and_class_restores_layer_colours(opened, qtbot) -> None:
    """View → Colour by offers class, enter, component and the file's attributes; choosing
    one changes the picture; Class turns the scalars off again."""
    win = opened
    menu = win.menus["colour_by"].menu()
    menu.aboutToShow.emit()
    titles = [action.text() for action in menu.actions()]
    assert titles[:3] == ["Class (layer colours)", "Alpha at which it appears",
                          "Solid component"]
    assert "Intensity" in titles and "RGB colours" in titles
    win.scene.plotter.render()
    qtbot.wait(20)
    plain = win.scene.plotter.screenshot(return_img=True)
    next(a for a in menu.actions() if a.text() == "Alpha at which it appears").trigger()
    win.scene.plotter.render()
    qtbot.wait(20)
    coloured = win.scene.plotter.screenshot(return_img=True)
    assert image_contrast(coloured) > 10
    assert np.abs(coloured.astype(int) - plain.astype(int)).sum(axis=2).astype(bool).mean() > 0.02
    next(a for a in menu.actions() if a.text() == "Class (layer colours)").trigger()
    assert not any(layer.actor.mapper.GetScalarVisibility()
                   for layer in win.scene.layers.values())
    bars = win.scene.plotter.scalar_bars
    assert bars == {} or "enters at alpha (r)" not in bars


def legend_lines(win) -> list[tuple[str, bool]]:
    """(text without its count, has a swatch) of each line of the drawn VTK legend."""
    legend = win.scene.overlay.legend
    return [(untallied(legend.GetEntryString(i)),
             legend.GetEntrySymbol(i).GetNumberOfPolys() > 0)
            for i in range(legend.GetNumberOfEntries())]


def untallied(text: str) -> str:
    """A legend line without the count of what it draws ('Singular edges: 12' -> 'Singular
    edges')."""
    return text.split(": ")[0]


def entries_of(overlay) -> list[tuple[str, str | None]]:
    """The overlay's legend entries without their counts."""
    return [(untallied(text), colour) for text, colour in overlay.entries]


def test_legend_follows_the_colour_mode(opened) -> None:
    """In class colours the legend shows each visible layer's swatch; while colouring by a value
    it says by what and drops the swatches of the painted layers (the colour bar is the key);
    back to class it shows the swatches again."""
    win = opened
    overlay = win.scene.overlay
    styles = win.scene.styles
    classed = [(untallied(text), True) for text, _ in overlay.entries]
    assert legend_lines(win) == classed and not overlay.entries[0][0].startswith("Coloured")
    assert entries_of(overlay) == merge_same_swatch([(LAYER_TITLES[name], style.colour)
                                                 for name, style in styles.items()
                                                 if style.visible])
    for key, title in (("enter", "enter alpha"),
                       ("component", "solid component"),
                       ("attribute:intensity", "intensity")):
        win.colourer.set_mode(key)
        painted = {name for name, layer in win.scene.layers.items()
                   if layer.actor.mapper.GetScalarVisibility()}
        assert "interior" in painted
        expected = merge_same_swatch([(f"Coloured by {title}", None)] + [
            (LAYER_TITLES[name], None if name in painted else style.colour)
            for name, style in styles.items() if style.visible])
        assert entries_of(overlay) == expected
        assert legend_lines(win) == [(text, colour is not None) for text, colour in expected]
        assert any(colour is None for _, colour in expected[1:])
    win.model.set_index(win.model.index + 1)  # a slider step keeps the mode's legend
    assert overlay.entries[0] == ("Coloured by intensity", None)
    win.colourer.set_mode("class")
    assert legend_lines(win) == classed
    assert entries_of(overlay) == merge_same_swatch([(LAYER_TITLES[name], style.colour)
                                                 for name, style in styles.items()
                                                 if style.visible])

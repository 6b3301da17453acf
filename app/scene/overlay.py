"""What makes a picture explain itself: a legend of the visible layers, the alpha (r and r²),
a scale bar in data units and an orientation marker, drawn over the scene (VTK, 2D actors).

While the layers are coloured by a value (View → Colour by) the legend says so and drops the
class swatch of every layer the colour map paints: the colour bar is then the key.

The scale bar follows the camera: it is resized before every render to a round length
(1, 2 or 5 times a power of ten) about a sixth of the view wide at the focal point.
"""

from __future__ import annotations

import math

import pyvista as pv
from vtkmodules.vtkCommonCore import vtkPoints
from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkPolyData
from vtkmodules.vtkRenderingCore import vtkActor2D, vtkPolyDataMapper2D, vtkTextActor

from app.numbers import decimals_for, quantity, with_unit
from app.palette import BACKGROUND, LAYER_TITLES, TEXT, LayerStyle

BAR_SHARE = 1 / 6  # the scale bar's target width, as a share of the view's
MARGIN = 12  # pixels from the view's edges
FONT_SIZE = 14
COUNT_ROOM = 4  # characters the legend keeps free for counts that grow with alpha
COUNT_WORDS = {"surface": " triangles", "interior": " cells"}  # what a count counts


def round_length(target: float) -> float:
    """The largest of 1, 2, 5 x 10^k not above target (target > 0)."""
    power = 10.0 ** math.floor(math.log10(target))
    return max(step * power for step in (1, 2, 5) if step * power <= target)


def length_label(length: float, unit: str | None) -> str:
    """A round length for the scale bar: '0.05', '2,000', or in metres '5,000 km', '20 m'."""
    if unit == "m" and length >= 1000:
        length, unit = length / 1000, "km"
    places = decimals_for(length) if length < 1 else 0
    return with_unit(f"{length:,.{places}f}", unit)


def legend_entries(styles: dict[str, LayerStyle], colour_by: str | None = None,
                   mapped: frozenset[str] = frozenset(), counts: dict[str, int] | None = None
                   ) -> list[tuple[str, str | None]]:
    """(label, swatch colour or None) per legend line: the visible layers in class colours, or
    while colouring by `colour_by` a first line saying so and no swatch on the `mapped` layers;
    a layer in `counts` says how many of its cells are drawn ('Singular points: 35')."""
    counts = counts or {}
    entries: list[tuple[str, str | None]] = [(f"Coloured by {colour_by}", None)] \
        if colour_by else []
    for name, style in styles.items():
        if style.visible:
            swatch = None if colour_by and name in mapped else style.colour
            title = LAYER_TITLES.get(name, name)
            count = f": {counts[name]:,}{COUNT_WORDS.get(name, '')}" if name in counts else ""
            entries.append((title + count, swatch))
    return merge_same_swatch(entries)


def merge_same_swatch(entries: list[tuple[str, str | None]]) -> list[tuple[str, str | None]]:
    """One line per swatch colour: layers drawn in one colour read as one part of the picture
    (3D: 'Surface + singular edges + singular points'); lines without a swatch stay apart."""
    merged: list[tuple[str, str | None]] = []
    line_of: dict[str, int] = {}
    for label, swatch in entries:
        if swatch is not None and swatch in line_of:
            i = line_of[swatch]
            merged[i] = (f"{merged[i][0]} + {label[:1].lower()}{label[1:]}", swatch)
            continue
        if swatch is not None:
            line_of[swatch] = len(merged)
        merged.append((label, swatch))
    return merged


def alpha_caption(alpha: float, unit: str | None) -> str:
    """'alpha: r 0.001105 m, r² 1.222e-06 m²' (weighted alphas may be negative: r² keeps the
    sign of the squared value)."""
    return (f"alpha: r {with_unit(quantity(alpha), unit)}, "
            f"r² {with_unit(quantity(alpha * abs(alpha)), unit, 2)}")


class Overlay:
    """The annotations of one plotter; `visible=False` leaves a clean figure."""

    def __init__(self, plotter: pv.BasePlotter) -> None:
        """Create the alpha text, scale bar and orientation marker (legend on first layers)."""
        self.plotter = plotter
        self.unit: str | None = None
        self.visible = True
        self.alpha = vtkTextActor()
        self._style_text(self.alpha)
        self.alpha.SetPosition(MARGIN, MARGIN)
        self.bar_label = vtkTextActor()
        self._style_text(self.bar_label)
        self.bar_label.GetTextProperty().SetJustificationToCentered()
        self.bar_points = vtkPoints()
        self.bar_points.SetNumberOfPoints(6)
        self.bar = self._bar_actor()
        for actor in (self.alpha, self.bar, self.bar_label):
            plotter.renderer.AddViewProp(actor)
        self.axes = plotter.add_axes(interactive=False, color=TEXT, line_width=2,
                                     viewport=(0.9, 0.0, 1.0, 0.14))
        self.legend = None
        self.entries: list[tuple[str, str | None]] = []  # what the legend shows, line by line
        self.styles: dict[str, LayerStyle] = {}
        self.colour_by: str | None = None
        self.mapped: frozenset[str] = frozenset()
        self.counts: dict[str, int] = {}  # drawn cells per layer, shown in the legend
        plotter.renderer.AddObserver("StartEvent", lambda *_: self.update_scale_bar())

    @staticmethod
    def _style_text(actor: vtkTextActor) -> None:
        prop = actor.GetTextProperty()
        prop.SetFontSize(FONT_SIZE)
        prop.SetColor(pv.Color(TEXT).float_rgb)
        prop.SetBackgroundColor(pv.Color(BACKGROUND).float_rgb)
        prop.SetBackgroundOpacity(0.6)

    def _bar_actor(self) -> vtkActor2D:
        """A bar with end ticks: three line segments in display coordinates."""
        lines = vtkCellArray()
        for a, b in ((0, 1), (2, 3), (4, 5)):
            lines.InsertNextCell(2)
            lines.InsertCellPoint(a)
            lines.InsertCellPoint(b)
        data = vtkPolyData()
        data.SetPoints(self.bar_points)
        data.SetLines(lines)
        mapper = vtkPolyDataMapper2D()
        mapper.SetInputData(data)
        actor = vtkActor2D()
        actor.SetMapper(mapper)
        actor.GetProperty().SetColor(pv.Color(TEXT).float_rgb)
        actor.GetProperty().SetLineWidth(2)
        return actor

    def set_alpha(self, alpha: float) -> None:
        """Show the current alpha (a radius; signed for weighted data)."""
        self.alpha.SetInput(alpha_caption(alpha, self.unit))

    def set_layers(self, styles: dict[str, LayerStyle]) -> None:
        """Legend of the visible layers, in their colours (only on a style change)."""
        self.styles = dict(styles)
        self._update_legend()

    def set_colour_by(self, title: str | None, mapped: frozenset[str] = frozenset()) -> None:
        """Colour-by mode `title` (None: class colours) painting the `mapped` layers."""
        self.colour_by, self.mapped = title, frozenset(mapped)
        self._update_legend()

    def set_counts(self, counts: dict[str, int]) -> None:
        """The drawn cells per layer at this alpha (on every step: the legend's lines are
        rewritten in place, the actor rebuilt only when its rows change)."""
        self.counts = dict(counts)
        self._update_legend()

    def _update_legend(self) -> None:
        """Rebuild the legend actor when its rows change (not on every alpha step: a new
        count only rewrites a row's text)."""
        entries = legend_entries(self.styles, self.colour_by, self.mapped, self.counts)
        if entries == self.entries and (self.legend is not None) == bool(entries):
            return
        same_rows = [c for _, c in entries] == [c for _, c in self.entries]
        if same_rows and self.legend is not None and entries:
            for row, ((text, _), (old, _)) in enumerate(zip(entries, self.entries, strict=True)):
                if text != old:
                    self.legend.SetEntryString(row, text)
            self.entries = entries
            return
        self.entries = entries
        if self.legend is not None:
            self.plotter.remove_legend(render=False)
            self.legend = None
        if entries:
            height = min(0.05 * len(entries), 0.4)
            labels = [[text, colour or TEXT, "rectangle" if colour else "none"]
                      for text, colour in entries]
            self.legend = self.plotter.add_legend(
                labels=labels, bcolor=BACKGROUND, border=True,
                size=(self._legend_width(entries), height), loc="upper left",
                background_opacity=0.6)
            self.legend.SetVisibility(self.visible)

    def _legend_width(self, entries: list[tuple[str, str | None]]) -> float:
        """Share of the picture's width for the legend: wide enough that a long merged line
        keeps a readable font (VTK scales the text to fit the box)."""
        longest = max(len(text) for text, _ in entries) + COUNT_ROOM
        return min(0.6, max(0.3 if self.colour_by else 0.22, 0.015 * longest))

    def set_visible(self, visible: bool) -> None:
        """Show or hide every annotation (--no-legend)."""
        self.visible = visible
        for actor in (self.alpha, self.bar, self.bar_label, self.axes, self.legend):
            if actor is not None:
                actor.SetVisibility(visible)

    def update_scale_bar(self) -> None:
        """Resize the scale bar to a round length in data units at the focal point."""
        renderer = self.plotter.renderer
        width, height = renderer.GetSize()
        per_pixel = self._world_per_pixel(height)
        if not self.visible or width <= 0 or not (per_pixel > 0 and math.isfinite(per_pixel)):
            self.bar.SetVisibility(False)
            self.bar_label.SetVisibility(False)
            return
        length = round_length(BAR_SHARE * width * per_pixel)
        pixels = length / per_pixel
        right = width - 0.12 * width - MARGIN
        left, y = right - pixels, MARGIN + 4
        for i, (x, dy) in enumerate(((left, 0), (right, 0), (left, -4), (left, 4),
                                     (right, -4), (right, 4))):
            self.bar_points.SetPoint(i, x, y + dy, 0.0)
        self.bar_points.Modified()
        self.bar_label.SetInput(length_label(length, self.unit))
        self.bar_label.SetPosition((left + right) / 2, y + 8)
        self.bar.SetVisibility(True)
        self.bar_label.SetVisibility(True)

    def _world_per_pixel(self, height: int) -> float:
        """Data units per pixel at the camera's focal point."""
        camera = self.plotter.renderer.GetActiveCamera()
        if height <= 0:
            return 0.0
        if camera.GetParallelProjection():
            return 2.0 * camera.GetParallelScale() / height
        view = math.radians(camera.GetViewAngle())
        return 2.0 * camera.GetDistance() * math.tan(view / 2) / height

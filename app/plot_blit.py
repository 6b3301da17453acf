"""Lines that move over a cached figure: a slider step redraws its cursors, not the figure.

A full matplotlib draw lays out and renders every tick, label, legend and curve of the
signatures figure (0.5-1 s a step on this machine class, benchmarks/bench_plot_cursor.py); the
cursors alone cost about a millisecond. The moving artists are `animated` (a full draw leaves
them out), the figure's pixels are copied after each full draw, and a move restores that copy,
draws the moving artists over it and asks Qt to paint the canvas from that buffer.
"""

from __future__ import annotations

from collections.abc import Iterable


class Blitter:
    """The moving artists of one Qt/Agg canvas drawn over the background of its last full draw.

    `move()` after changing the artists' data: blits them over the cached background, or asks
    for one full draw when there is none (first draw, a resize, `redraw()`).
    """

    def __init__(self, canvas, artists: Iterable) -> None:
        """Animate `artists` (matplotlib artists on canvas's figure) and follow its draws."""
        self.canvas = canvas
        self.artists = list(artists)
        for artist in self.artists:
            artist.set_animated(True)
        self.background = None
        self.bounds: tuple[float, ...] | None = None
        self.full_draws = 0  # how many full draws the canvas made (the cursors never cause one)
        canvas.mpl_connect("draw_event", self._drawn)

    def _drawn(self, event) -> None:
        """After a full draw: keep its pixels as the background, put the artists over them
        (the paint that follows copies the buffer with them). Draws of another canvas (the
        figure saved to a file) leave the cache alone."""
        if event.canvas is not self.canvas:
            return
        self.full_draws += 1
        figure = self.canvas.figure
        self.background = self.canvas.copy_from_bbox(figure.bbox)
        self.bounds = tuple(figure.bbox.bounds)
        self._draw_artists()

    def _draw_artists(self) -> None:
        """Draw the visible moving artists into the canvas's buffer."""
        figure = self.canvas.figure
        for artist in self.artists:
            if artist.get_visible() and (artist.axes is None or artist.axes.get_visible()):
                figure.draw_artist(artist)

    def redraw(self) -> None:
        """The figure itself changed: forget the background, one full draw (coalesced)."""
        self.background = None
        self.canvas.draw_idle()

    def move(self) -> bool:
        """Show the artists' new data: True when drawn over the cached background, False
        when a full draw was asked for instead (no background of the canvas's size yet)."""
        if self.background is None or self.bounds != tuple(self.canvas.figure.bbox.bounds):
            self.redraw()
            return False
        self.canvas.restore_region(self.background)
        self._draw_artists()
        # not canvas.blit: its synchronous repaint composes the whole window on its own (the
        # window holds an OpenGL widget: ~60 ms in software GL); update() joins the paint of
        # the step's other widgets and 3D view in one composition
        self.canvas.update()
        return True

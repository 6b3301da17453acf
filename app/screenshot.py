"""Non-interactive mode: render a file at one alpha into a PNG and exit (no window, no Qt)."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import pyvista as pv

from app.loading import read_points
from app.resources import SAMPLE_PATH
from app.scene import Scene
from core.errors import AlphaScoopError

DEFAULT_SIZE = (1280, 800)


def render_png(source: Path, out: Path, size: tuple[int, int]) -> None:
    """Render source's points into out (PNG) with an off-screen plotter of size pixels."""
    plotter = pv.Plotter(off_screen=True, window_size=list(size))
    try:
        plotter.set_background("#1f2a36")
        scene = Scene(plotter)
        scene.set_points(read_points(source))
        plotter.screenshot(str(out))
    finally:
        plotter.close()


def run_screenshot(args: argparse.Namespace) -> int:
    """Save the screenshot args asks for; 0 on success, 1 with a message on failure."""
    source = Path(args.file) if args.file else SAMPLE_PATH
    out = Path(args.screenshot)
    try:
        render_png(source, out, args.size or DEFAULT_SIZE)
    except (AlphaScoopError, OSError) as error:
        print(f"alphascoop: {error}", file=sys.stderr)
        return 1
    print(f"wrote {out}")
    return 0

"""Non-interactive mode: render a file's shape at one alpha into a PNG and exit (no Qt).

`alphascoop FILE --alpha R --screenshot OUT.png [--size WxH]` (or `--optimal`) uses an
off-screen VTK plotter, so it also works with no display at all.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import pyvista as pv

from app.dataset import Dataset, ImportOptions, load_dataset
from app.palette import default_styles
from app.resources import SAMPLE_PATH
from app.scene import Scene, as_xyz
from core.atomic import atomic_path
from core.complex import at_value
from core.errors import AlphaScoopError

DEFAULT_SIZE = (1280, 800)


def quiet_progress(fraction: float, stage: str) -> None:
    """Progress sink for scripts: says nothing."""


def render_png(dataset: Dataset, alpha: float, out: Path, size: tuple[int, int],
               legend: bool = True) -> None:
    """Render dataset's shape at alpha into out (PNG, written atomically) at size pixels, with
    the legend, alpha, scale bar and orientation marker unless `legend` is False."""
    ac = dataset.ac
    plotter = pv.Plotter(off_screen=True, window_size=list(size))
    try:
        scene = Scene(plotter)
        scene.set_dataset(as_xyz(ac.to_ambient(ac.points)), ac.dim, ac.simplices(1),
                          default_styles(ac.dim), frame=dataset.frame, unit=dataset.unit)
        scene.overlay.set_visible(legend)
        scene.set_shape(ac.shape(**at_value(alpha)))  # weighted: may be below zero
        with atomic_path(out) as tmp:
            save_png(plotter, tmp)
    finally:
        plotter.close()


def save_png(plotter: pv.Plotter, path: Path) -> None:
    """Write the plotter's image to path as PNG, whatever path's extension."""
    from PIL import Image

    Image.fromarray(plotter.screenshot(return_img=True)).save(path, format="PNG")


def run_screenshot(args: argparse.Namespace) -> int:
    """Save the screenshot args asks for; 0 on success, 1 with a message on failure."""
    source = Path(args.file) if args.file else SAMPLE_PATH
    out = Path(args.screenshot)
    try:
        if not out.parent.is_dir():
            raise AlphaScoopError(f"{out.parent}: no such folder for the screenshot")
        dataset = load_dataset(source, quiet_progress, mode=getattr(args, "mode", None),
                               options=ImportOptions(columns=args.columns,
                                                     subsample=args.subsample))
        alpha = dataset.optimal_alpha if args.optimal else args.alpha
        alpha = dataset.default_alpha if alpha is None else alpha
        render_png(dataset, alpha, out, args.size or DEFAULT_SIZE, legend=not args.no_legend)
    except (AlphaScoopError, OSError) as error:
        print(f"alphascoop: {error}", file=sys.stderr)
        return 1
    shown = (f"alpha² {alpha * abs(alpha):.6g}" if dataset.ac.weights is not None
             else f"alpha {alpha:.6g}")
    print(f"wrote {out} ({shown})")
    return 0

"""Non-interactive mode: render a file's shape at one alpha into a PNG and exit (no Qt).

`alphascoop FILE --alpha R --screenshot OUT.png [--size WxH]` (or `--optimal`) draws the
same scene as the window (app.scene) into an off-screen plotter, so it also works with no
display at all.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from app.dataset import Dataset, ImportOptions, load_dataset
from app.palette import default_styles
from app.resources import SAMPLE_PATH
from app.scene import Scene, scene_data
from core.complex import at_value
from core.errors import AlphaScoopError

DEFAULT_SIZE = (1280, 800)


def quiet_progress(fraction: float, stage: str) -> None:
    """Progress sink for scripts: says nothing."""


def render_png(dataset: Dataset, alpha: float, out: Path, size: tuple[int, int],
               legend: bool = True) -> None:
    """Render dataset's shape at alpha into out (PNG, written atomically) at size pixels, with
    the legend, alpha, scale bar and orientation marker unless `legend` is False."""
    scene = Scene.off_screen(size)
    try:
        scene.set_dataset(scene_data(dataset, default_styles(dataset.ac.dim)))
        scene.overlay.set_visible(legend)
        scene.set_shape(dataset.ac.shape(**at_value(alpha)))  # weighted: may be below zero
        scene.save_png(out)
    finally:
        scene.close()


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

"""Entry point of `alphascoop` and `python -m app`: subcommands, or the explorer window.

Qt is imported only inside functions, so `alphascoop info ...` runs without a display.
"""

from __future__ import annotations

import argparse
import os
import sys
from collections.abc import Sequence

from app.args import add_mode_options, count, mode_of, negative_values_joined, radius

SUBCOMMANDS = ("info", "export")
NO_DISPLAY_MESSAGE = (
    "alphascoop: no display found (DISPLAY and WAYLAND_DISPLAY are not set).\n"
    "Run the window under a virtual X server instead:\n"
    "    xvfb-run -a .venv/bin/alphascoop [FILE]\n"
    "or make a picture without a window:\n"
    "    .venv/bin/alphascoop FILE --optimal --screenshot out.png"
)


def parse_size(text: str) -> tuple[int, int]:
    """Parse 'WxH' (e.g. 1280x800) into positive (width, height) pixels."""
    try:
        width, height = (int(part) for part in text.lower().split("x"))
    except ValueError:
        raise argparse.ArgumentTypeError(f"size must look like 1280x800, not {text!r}") from None
    if not (16 <= width <= 8192 and 16 <= height <= 8192):
        raise argparse.ArgumentTypeError(f"size {text!r} must be 16..8192 pixels each way")
    return width, height


def window_parser() -> argparse.ArgumentParser:
    """The window's command line: [FILE] [--alpha R | --optimal] [--columns A,B[,C]]
    [--subsample N] [--screenshot OUT] [--size WxH]."""
    parser = argparse.ArgumentParser(
        prog="alphascoop",
        description="Explore alpha shapes of 2D/3D point sets. "
        "Subcommands: `alphascoop info FILE`, `alphascoop export ...` (see their --help).",
    )
    parser.add_argument("file", nargs="?", help="point file to open (default: bundled sample)")
    choice = parser.add_mutually_exclusive_group()
    choice.add_argument("--alpha", type=radius, metavar="R", help="alpha radius to show")
    choice.add_argument("--optimal", action="store_true", help="open at CGAL's optimal alpha "
                        "(default: the opening alpha, where the shape looks like the object)")
    parser.add_argument("--columns", metavar="A,B[,C]",
                        help="coordinate columns of a text or NumPy file (names or 0-based)")
    parser.add_argument("--subsample", type=count, metavar="N", help="thin to at most N points")
    parser.add_argument("--screenshot", metavar="OUT.png", help="render, save an image, exit")
    parser.add_argument("--size", type=parse_size, metavar="WxH", help="window/image size")
    parser.add_argument("--no-legend", action="store_true",
                        help="screenshot without legend, alpha, scale bar and axes")
    add_mode_options(parser)
    return parser


def has_display() -> bool:
    """False on Linux when Qt would find no display server (and none was chosen explicitly)."""
    if not sys.platform.startswith("linux"):
        return True
    return any(os.environ.get(name) for name in ("DISPLAY", "WAYLAND_DISPLAY", "QT_QPA_PLATFORM"))


def run_subcommand(argv: list[str]) -> int:
    """Hand `info`/`export` to app.cli (imported lazily; it needs no Qt)."""
    try:
        from app import cli
    except ImportError:
        print(f"alphascoop {argv[0]}: not available yet", file=sys.stderr)
        return 2
    return int(cli.main(argv) or 0)


def main(argv: Sequence[str] | None = None) -> int:
    """Run alphascoop with argv (default sys.argv[1:]); return the exit status."""
    args_list = list(sys.argv[1:] if argv is None else argv)
    if args_list and args_list[0] in SUBCOMMANDS:
        return run_subcommand(args_list)
    parser = window_parser()
    try:
        args = parser.parse_args(negative_values_joined(args_list))
        try:
            args.mode = mode_of(args)
        except ValueError as exc:
            parser.error(str(exc))
    except SystemExit as exit_:
        return int(exit_.code or 0)
    os.environ["QT_API"] = "pyside6"
    if args.screenshot:
        if not has_display():
            os.environ.setdefault("VTK_DEFAULT_OPENGL_WINDOW", "vtkEGLRenderWindow")
        from app.screenshot import run_screenshot

        return run_screenshot(args)
    if not has_display():
        print(NO_DISPLAY_MESSAGE, file=sys.stderr)
        return 2
    from app.launch import run_window

    return run_window(args)


if __name__ == "__main__":
    sys.exit(main())

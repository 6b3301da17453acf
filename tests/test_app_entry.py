"""The `alphascoop` entry point: argument handling, subcommand hand-off, no-display message,
and the non-interactive screenshot mode."""

from __future__ import annotations

import os
import subprocess
import sys
import types

import numpy as np
import pytest
from conftest import image_contrast
from PIL import Image

from app.__main__ import main, parse_size
from app.resources import SAMPLE_PATH

MIN_CONTRAST = 10.0


def run_app(*args: str, display: bool = False) -> subprocess.CompletedProcess:
    """Run `python -m app args` in a fresh process, with or without a display."""
    env = dict(os.environ)
    if not display:
        for name in ("DISPLAY", "WAYLAND_DISPLAY", "QT_QPA_PLATFORM"):
            env.pop(name, None)
    return subprocess.run([sys.executable, "-m", "app", *args], env=env, capture_output=True,
                          text=True, timeout=300)


def test_help_exits_zero(capsys) -> None:
    """--help prints usage and returns 0 (not SystemExit)."""
    assert main(["--help"]) == 0
    assert "--screenshot" in capsys.readouterr().out


@pytest.mark.parametrize("argv", [["--size", "big"], ["--alpha", "-1"], ["--alpha", "x"],
                                  ["--alpha", "nan"], ["--alpha", "inf"],
                                  ["--alpha", "1", "--optimal"], ["a", "b"]])
def test_bad_arguments_return_2_with_a_message(argv, capsys) -> None:
    """Malformed options give status 2 and a usage message, never a traceback."""
    assert main(argv) == 2
    assert "usage: alphascoop" in capsys.readouterr().err


@pytest.mark.parametrize("text", ["-1", "nan", "inf", "1e999", "x"])
def test_window_and_subcommands_refuse_the_same_alphas(text, capsys) -> None:
    """One radius check for both entry points: `--alpha` means the same everywhere."""
    assert main(["--alpha", text]) == 2
    assert "alpha must be" in capsys.readouterr().err
    for command in (["info", "x.ply"], ["export", "x.ply", "-o", "y.ply"]):
        assert main([*command, "--alpha", text]) == 2
        assert "alpha must be" in capsys.readouterr().err


@pytest.mark.parametrize(("text", "value"), [("0", 0.0), ("0.25", 0.25), ("1e-3", 1e-3)])
def test_window_and_subcommands_accept_the_same_alphas(text, value) -> None:
    """Finite radii >= 0 parse to the same value in both parsers."""
    from app import cli
    from app.__main__ import window_parser

    assert window_parser().parse_args(["--alpha", text]).alpha == value
    parsed = cli.build_parser().parse_args(["info", "x.ply", "--alpha", text])
    assert parsed.alpha == value


@pytest.mark.parametrize(("text", "size"), [("640x480", (640, 480)), ("16X16", (16, 16))])
def test_parse_size(text, size) -> None:
    """WxH sizes parse either case of x."""
    assert parse_size(text) == size


@pytest.mark.parametrize("command", ["info", "export"])
def test_subcommands_go_to_app_cli(command, monkeypatch) -> None:
    """`info`/`export` are handed to app.cli.main with the full argv."""
    calls: list[list[str]] = []
    fake = types.ModuleType("app.cli")
    fake.main = lambda argv: calls.append(argv) or 7
    monkeypatch.setitem(sys.modules, "app.cli", fake)
    monkeypatch.setattr("app.cli", fake, raising=False)
    assert main([command, "x.ply"]) == 7
    assert calls == [[command, "x.ply"]]


def test_window_without_display_says_how_to_run_it() -> None:
    """No display: a clear hint to use xvfb-run, status 2, no Qt abort or traceback."""
    result = run_app()
    assert result.returncode == 2
    assert "xvfb-run -a .venv/bin/alphascoop" in result.stderr
    assert "Traceback" not in result.stderr


def test_screenshot_mode_renders_two_different_alphas(tmp_path) -> None:
    """--screenshot works with no display; the optimal shape and a tiny alpha differ."""
    optimal, tiny = tmp_path / "optimal.png", tmp_path / "tiny.png"
    for out, choice in ((optimal, ["--optimal"]), (tiny, ["--alpha", "0.03"])):
        result = run_app(str(SAMPLE_PATH), *choice, "--screenshot", str(out), "--size", "320x240")
        assert result.returncode == 0, result.stderr
    images = [np.asarray(Image.open(path).convert("RGB")) for path in (optimal, tiny)]
    assert images[0].shape == (240, 320, 3)
    assert all(image_contrast(image) > MIN_CONTRAST for image in images)
    assert np.abs(images[0].astype(int) - images[1].astype(int)).mean() > 1.0


def test_screenshot_of_a_missing_file_fails_cleanly(tmp_path) -> None:
    """A missing input gives status 1 and one readable line, and writes nothing."""
    out = tmp_path / "never.png"
    result = run_app(str(tmp_path / "missing.ply"), "--screenshot", str(out))
    assert result.returncode == 1
    assert "missing.ply" in result.stderr and "Traceback" not in result.stderr
    assert not out.exists()

"""The app's bundled files (sample point set, icon): package data of `app`, found through
importlib.resources, so an installed wheel finds them as a source checkout does."""

from __future__ import annotations

from importlib.resources import files
from pathlib import Path


def asset(name: str) -> Path:
    """Path of the bundled file `name` in app/assets (installed with the package)."""
    return Path(str(files("app").joinpath("assets", name)))


SAMPLE_PATH = asset("sample.ply")
ICON_PATH = asset("icon.svg")

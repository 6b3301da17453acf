"""The app's bundled files (sample point set, icon), found through importlib.resources.

They live in the top-level assets/ folder; app/assets is a link to it, so in a checkout they
are package data of `app` like in an installed wheel, where pyproject.toml's package-data
copies them into app/assets. No path is computed from the repository's layout.
"""

from __future__ import annotations

from importlib.resources import files
from pathlib import Path


def asset(name: str) -> Path:
    """Path of the bundled file `name` (app/assets/name, installed with the package)."""
    return Path(str(files("app").joinpath("assets", name)))


SAMPLE_PATH = asset("sample.ply")
ICON_PATH = asset("icon.svg")

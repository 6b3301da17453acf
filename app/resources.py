"""Where the app's bundled files live (sample point set, icon)."""

from __future__ import annotations

from pathlib import Path

ASSETS = Path(__file__).resolve().parent.parent / "assets"
SAMPLE_PATH = ASSETS / "sample.ply"
ICON_PATH = ASSETS / "icon.svg"

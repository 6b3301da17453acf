"""Regenerate the README's pictures of the alpha modes with the window's screenshot mode.

    python assets/pictures/modes/make_pictures.py

Writes two small data sets beside this script (disks.npz: a dense and a sparse disk;
sheets.npz: two noisy parallel walls 0.5 apart, sampled at spacing 1) and renders each with
`alphascoop FILE --alpha R --screenshot OUT.png`, classic and in its mode, at the alphas named
below (the smallest ones where the mode closes both parts while keeping them apart, and
classic alphas where its parts are just closed).
"""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[2]
SIZE = "480x360"


def jittered_grid(step: float, size: float, rng, height: float | None = None) -> np.ndarray:
    """(n, 2) grid over [0, size] x [0, height (default size)] moved by up to a quarter step."""
    axis = np.arange(0.0, size + 1e-9, step)
    other = axis if height is None else np.arange(0.0, height + 1e-9, step)
    grid = np.stack(np.meshgrid(axis, other), axis=-1).reshape(-1, 2)
    return grid + rng.uniform(-0.25 * step, 0.25 * step, grid.shape)


def disks() -> np.ndarray:
    """A disk sampled at spacing 0.04 beside one sampled at 0.25, 0.2 apart."""
    rng = np.random.default_rng(3)
    parts = []
    for step, centre in ((0.04, 0.0), (0.25, 2.2)):
        grid = jittered_grid(step, 2.0, rng) - 1.0
        parts.append(grid[(grid**2).sum(axis=1) <= 1.0] + [centre, 0.0])
    return np.vstack(parts)


def sheets() -> np.ndarray:
    """Two upright 6 x 3 walls at spacing 1, 0.5 apart along y, with noise 0.02 across them
    (upright so that the default camera, from above, looks into the gap)."""
    rng = np.random.default_rng(0)
    walls = []
    for offset in (0.0, 0.5):
        grid = jittered_grid(1.0, 6, rng, 3)
        walls.append(np.column_stack([grid[:, 0], offset + rng.normal(0, 0.02, len(grid)),
                                      grid[:, 1]]))
    return np.vstack(walls)


def shoot(data: Path, alpha: float, out: str, *mode: str) -> None:
    """One screenshot of `data` at `alpha` (in the mode's units) into HERE/out."""
    subprocess.run([sys.executable, "-m", "app", str(data), "--alpha", str(alpha),
                    "--screenshot", str(HERE / out), "--size", SIZE, *mode],
                   check=True, cwd=ROOT)


def main() -> None:
    np.savez(HERE / "disks.npz", points=disks())
    np.savez(HERE / "sheets.npz", points=sheets())
    shoot(HERE / "disks.npz", 0.3, "disks_classic.png")
    shoot(HERE / "disks.npz", 0.55, "disks_density.png", "--density", "8")
    shoot(HERE / "sheets.npz", 0.9, "sheets_classic.png")
    shoot(HERE / "sheets.npz", 0.95, "sheets_anisotropic.png", "--anisotropic", "0.9")


if __name__ == "__main__":
    main()

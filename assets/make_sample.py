"""Write assets/sample.ply: a trefoil-knot tube (a tunnel) and a thick hollow ball (a void).

The two solids are separate components, so one alpha shows two components, a tunnel and a void;
run `python assets/make_sample.py` to regenerate it byte for byte (fixed seed).
"""

from __future__ import annotations

import os
import tempfile
from pathlib import Path

import numpy as np
from plyfile import PlyData, PlyElement
from scipy.spatial import cKDTree

SEED = 20261122
KNOT_POINTS = 12_000
SHELL_POINTS = 6_000
TUBE_RADIUS = 0.32
SHELL_RADII = (0.55, 0.8)
SHELL_CENTRE = np.array([5.0, 0.0, 0.0])
NOISE = 0.004


def trefoil(t: np.ndarray) -> np.ndarray:
    """(k, 3) float64 points of a (2, 3) torus knot at parameters t (k,)."""
    ring = 2.0 + np.cos(3.0 * t)
    return np.column_stack([ring * np.cos(2.0 * t), ring * np.sin(2.0 * t), np.sin(3.0 * t)])


def knot_tube(rng: np.random.Generator, n: int) -> np.ndarray:
    """(n, 3) points uniform in the solid tube of radius TUBE_RADIUS around the trefoil."""
    tree = cKDTree(trefoil(np.linspace(0.0, 2.0 * np.pi, 20_000)))
    lo, hi = np.array([-3.4, -3.4, -1.4]), np.array([3.4, 3.4, 1.4])
    kept: list[np.ndarray] = []
    while sum(len(k) for k in kept) < n:
        batch = rng.uniform(lo, hi, size=(200_000, 3))
        distance, _ = tree.query(batch)
        kept.append(batch[distance < TUBE_RADIUS])
    return np.concatenate(kept)[:n]


def hollow_ball(rng: np.random.Generator, n: int) -> np.ndarray:
    """(n, 3) points uniform in the spherical shell SHELL_RADII around SHELL_CENTRE."""
    direction = rng.normal(size=(n, 3))
    direction /= np.linalg.norm(direction, axis=1, keepdims=True)
    r_in, r_out = SHELL_RADII
    radius = np.cbrt(rng.uniform(r_in**3, r_out**3, size=n))
    return SHELL_CENTRE + direction * radius[:, None]


def make_points(seed: int = SEED) -> np.ndarray:
    """(n, 3) float32 sample points: knot tube plus hollow ball, with a little noise."""
    rng = np.random.default_rng(seed)
    points = np.concatenate([knot_tube(rng, KNOT_POINTS), hollow_ball(rng, SHELL_POINTS)])
    points += rng.normal(scale=NOISE, size=points.shape)
    return points.astype(np.float32)


def write_ply(points: np.ndarray, path: Path) -> None:
    """Write (n, 3) float32 points as a binary PLY, atomically (temp file + os.replace)."""
    vertex = np.empty(len(points), dtype=[("x", "<f4"), ("y", "<f4"), ("z", "<f4")])
    vertex["x"], vertex["y"], vertex["z"] = points.T
    ply = PlyData([PlyElement.describe(vertex, "vertex")], text=False, byte_order="<")
    ply.comments.append("Alpha Scoop sample: trefoil knot tube + hollow ball (make_sample.py)")
    fd, tmp = tempfile.mkstemp(dir=path.parent, suffix=".tmp")
    try:
        with os.fdopen(fd, "wb") as stream:
            ply.write(stream)
        os.chmod(tmp, 0o644)
        os.replace(tmp, path)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise


if __name__ == "__main__":
    target = Path(__file__).resolve().parent / "sample.ply"
    write_ply(make_points(), target)
    print(f"wrote {target} ({target.stat().st_size} bytes)")

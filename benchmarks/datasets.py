"""Deterministic benchmark point sets: a scan-like noisy torus surface sample."""

from __future__ import annotations

import os
import tempfile

import numpy as np

TORUS_R = 1.0
TORUS_TUBE = 0.35
NOISE_FRACTION = 0.003


def noisy_torus(
    n: int,
    seed: int = 0,
    major: float = TORUS_R,
    minor: float = TORUS_TUBE,
    noise: float = NOISE_FRACTION,
) -> np.ndarray:
    """(n, 3) float64 area-uniform torus surface sample with range-like noise along the normal.

    The displacement is Gaussian with sigma = noise * minor, so the sample is a thin shell around
    the surface as a laser scan is; the same (n, seed) always gives the same points.
    """
    if n < 4:
        raise ValueError(f"a benchmark torus needs at least 4 points, got {n}")
    rng = np.random.default_rng(seed)
    u = rng.uniform(0.0, 2.0 * np.pi, n)
    v = _tube_angles(rng, n, major, minor)
    tube = minor + rng.normal(0.0, noise * minor, n)
    ring = major + tube * np.cos(v)
    return np.column_stack((ring * np.cos(u), ring * np.sin(u), tube * np.sin(v)))


def _tube_angles(rng: np.random.Generator, n: int, major: float, minor: float) -> np.ndarray:
    """(n,) float64 tube angles with density proportional to the torus area element (rejection)."""
    kept = np.empty(0)
    while kept.size < n:
        v = rng.uniform(0.0, 2.0 * np.pi, 2 * (n - kept.size) + 16)
        accept = rng.uniform(0.0, major + minor, v.size) < major + minor * np.cos(v)
        kept = np.concatenate((kept, v[accept]))
    return kept[:n]


def write_points(points: np.ndarray, path: str) -> None:
    """Save (n, d) float64 points as .npy atomically (temp file + os.replace)."""
    folder = os.path.dirname(os.path.abspath(path))
    fd, tmp = tempfile.mkstemp(suffix=".npy", dir=folder)
    try:
        with os.fdopen(fd, "wb") as handle:
            np.save(handle, np.ascontiguousarray(points, dtype=np.float64))
        os.replace(tmp, path)
    except BaseException:
        os.unlink(tmp)
        raise


def read_points(path: str) -> np.ndarray:
    """(n, d) float64 points from a .npy written by write_points (never unpickles)."""
    return np.load(path, allow_pickle=False)


def write_torus(n: int, seed: int, path: str) -> dict:
    """Generate the benchmark torus and save it; returns {'n': n, 'seed': seed} for the log."""
    write_points(noisy_torus(n, seed), path)
    return {"n": n, "seed": seed}

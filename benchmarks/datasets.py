"""Deterministic benchmark point sets: a scan-like noisy torus surface sample."""

from __future__ import annotations

import os
import tempfile
from pathlib import Path

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


def write_torus_las(n: int, seed: int, path: str, chunk: int = 1 << 20,
                    scale: float = 1e-7) -> None:
    """A noisy torus of n points as a LAS file written chunk by chunk (no array of all n
    points): chunk i is noisy_torus(chunk, seed * 1_000_003 + i), an area-uniform sample as
    the whole is; coordinates stored on a `scale` grid, as a scanner's are."""
    import laspy

    header = laspy.LasHeader(point_format=0, version="1.2")
    header.scales = np.full(3, scale)
    header.offsets = np.zeros(3)
    folder = os.path.dirname(os.path.abspath(path))
    fd, tmp = tempfile.mkstemp(suffix=".las", dir=folder)
    os.close(fd)
    try:
        with laspy.open(tmp, mode="w", header=header) as writer:
            for i, lo in enumerate(range(0, n, chunk)):
                xyz = noisy_torus(min(chunk, n - lo), seed * 1_000_003 + i)
                record = laspy.ScaleAwarePointRecord.zeros(len(xyz), header=header)
                record.x, record.y, record.z = xyz.T
                writer.write_points(record)
        os.replace(tmp, path)
    except BaseException:
        os.unlink(tmp)
        raise


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


def shared_data() -> Path:
    """The folder of the real scans: shared/data beside the repository, else $ALPHASCOOP_DATA
    (the tests' rule, tests/reference.py)."""
    here = Path(__file__).resolve().parents[2] / "shared" / "data"
    env = os.environ.get("ALPHASCOOP_DATA")
    return here if here.is_dir() or not env else Path(env)


def bunny_scan(n: int, seed: int = 0, mesh: str | None = None) -> np.ndarray:
    """(n, 3) float64 scan-like sample of the Stanford bunny (shared/data/bunny.ply's faces):
    area-uniform on the mesh, moved along each face normal by Gaussian range noise of sigma
    0.05 mm, coordinates rounded to 1 µm as the ASCII PLY stores them (metres)."""
    from plyfile import PlyData

    path = mesh or shared_data() / "bunny.ply"
    ply = PlyData.read(path)
    vertex = ply["vertex"]
    corners = np.column_stack([vertex["x"], vertex["y"], vertex["z"]]).astype(np.float64)
    faces = np.vstack(ply["face"]["vertex_indices"]).astype(np.int64)
    a, b, c = (corners[faces[:, k]] for k in range(3))
    normal = np.cross(b - a, c - a)
    area = np.linalg.norm(normal, axis=1)
    rng = np.random.default_rng(seed)
    pick = rng.choice(len(faces), size=n, p=area / area.sum())
    u, v = rng.random(n), rng.random(n)
    flip = u + v > 1
    u[flip], v[flip] = 1 - u[flip], 1 - v[flip]
    unit = normal[pick] / area[pick, None]
    points = (a[pick] + u[:, None] * (b[pick] - a[pick]) + v[:, None] * (c[pick] - a[pick])
              + rng.normal(0.0, 5e-5, n)[:, None] * unit)
    return np.round(points, 6)

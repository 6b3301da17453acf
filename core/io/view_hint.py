"""Which way is up in a file's coordinates, where the file says it (no Qt): the readers hand a
ViewHint to the load report beside their notes; the app's camera reads it from there.

LiDAR (LAS/LAZ) and geographic data have z up; an E57 scan's pose rotates the scanner's own z
(its up) into the file's frame; a PCD file's VIEWPOINT is the sensor's pose (PCL's camera
frame: looking along +z, y down), so it gives the sensor's forward direction too.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class ViewHint:
    """Up (3,) and, for a sensor's view, `front` (3,) unit vectors in the file's coordinates
    (None: not said); `source` says where they came from, in words."""

    up: tuple[float, float, float]
    front: tuple[float, float, float] | None
    source: str


Z_UP_HINT = (0.0, 0.0, 1.0)


def quaternion_matrix(w: float, x: float, y: float, z: float) -> np.ndarray:
    """(3, 3) rotation of a quaternion (w, x, y, z), normalised first (identity if zero)."""
    q = np.array([w, x, y, z], dtype=float)
    norm = np.linalg.norm(q)
    if not np.isfinite(norm) or norm == 0:
        return np.eye(3)
    w, x, y, z = q / norm
    return np.array([
        [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
        [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
        [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)],
    ])


def unit(vector) -> tuple[float, float, float]:
    """The (3,) vector scaled to length 1, as a tuple of floats."""
    v = np.asarray(vector, dtype=float)
    return tuple(float(c) for c in v / np.linalg.norm(v))


def sensor_hint(words: list[str] | None) -> ViewHint | None:
    """The sensor's view from a PCD VIEWPOINT (tx ty tz qw qx qy qz), or None when absent or
    not seven numbers."""
    try:
        values = [float(v) for v in words] if words else []
    except ValueError:
        return None
    if len(values) != 7 or not np.all(np.isfinite(values)):
        return None
    rotation = quaternion_matrix(*values[3:])
    return ViewHint(up=unit(rotation @ [0.0, -1.0, 0.0]), front=unit(rotation @ [0.0, 0.0, 1.0]),
                    source="PCD VIEWPOINT (the sensor's view)")


def pose_hint(rotation: np.ndarray) -> ViewHint:
    """Up from an E57 scan pose's (3, 3) rotation: the scanner's z in the file's frame."""
    return ViewHint(up=unit(np.asarray(rotation, dtype=float) @ [0.0, 0.0, 1.0]), front=None,
                    source="E57 scan pose")

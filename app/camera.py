"""Which way is up, and the view presets (top, front, side, iso), from what the file says (no Qt).

LiDAR (LAS/LAZ, E57) and geographic data have z up; a PCD file's VIEWPOINT is the sensor's
pose (PCL's camera frame: looking along +z, y down), so its front view is the sensor's own;
meshes and scans in graphics formats (PLY, OBJ, OFF, glTF: the Stanford scans among them)
have y up; everything else gets z up, the usual convention of scanners and GIS.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

Z_UP_FORMATS = {"LAS", "LAZ", "E57"}
Y_UP_SUFFIXES = {".ply", ".obj", ".off", ".glb", ".gltf"}
PRESETS = ("top", "front", "side", "iso")


@dataclass(frozen=True)
class ViewFrame:
    """Up (3,) and front (3,) unit vectors: the front view looks along `front` with `up` up;
    `start` is the preset a dataset opens with."""

    up: tuple[float, float, float]
    front: tuple[float, float, float]
    start: str = "iso"

    def direction(self, preset: str) -> tuple[np.ndarray, np.ndarray]:
        """(look direction, view up), unit (3,) float64 each, of a preset in PRESETS."""
        up, front = np.asarray(self.up, dtype=float), np.asarray(self.front, dtype=float)
        right = np.cross(front, up)
        if preset == "top":
            return -up, front
        if preset == "front":
            return front, up
        if preset == "side":
            return -right, up
        if preset == "iso":  # from front right, above; the view up made perpendicular
            look = front - right - 0.8 * up
            look /= np.linalg.norm(look)
            view_up = up - (up @ look) * look
            return look, view_up / np.linalg.norm(view_up)
        raise ValueError(f"unknown view preset {preset!r}; choose one of {', '.join(PRESETS)}")


Z_UP = ViewFrame(up=(0.0, 0.0, 1.0), front=(0.0, 1.0, 0.0))
Y_UP = ViewFrame(up=(0.0, 1.0, 0.0), front=(0.0, 0.0, -1.0))


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


def pcd_frame(path: Path) -> ViewFrame | None:
    """The sensor's view of a PCD file from its VIEWPOINT (tx ty tz qw qx qy qz), or None."""
    from core.errors import AlphaScoopError
    from core.io.pcd_checks import check_pcd_header

    try:
        words = check_pcd_header(path)[1].get("VIEWPOINT")
        values = [float(v) for v in words] if words else []
    except (AlphaScoopError, OSError, ValueError):
        return None
    if len(values) != 7:
        return None
    rotation = quaternion_matrix(*values[3:])
    return ViewFrame(up=tuple(rotation @ [0.0, -1.0, 0.0]), front=tuple(rotation @ [0.0, 0.0, 1.0]),
                     start="front")


def frame_for(path: Path, report) -> ViewFrame:
    """The view frame of a dataset read from path with this LoadReport (None allowed)."""
    path = Path(path)
    if path.suffix.lower() == ".pcd":
        frame = pcd_frame(path)
        if frame is not None:
            return frame
    if report is not None and (report.format in Z_UP_FORMATS or report.georef is not None):
        return Z_UP
    return Y_UP if path.suffix.lower() in Y_UP_SUFFIXES else Z_UP

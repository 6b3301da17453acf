"""Which way is up, where a dataset opens from, and the view presets (top, front, side, iso),
from what the file says and the points' own shape (no Qt).

A dataset opens looking along its thinnest principal axis (a scan's surface faces the viewer,
a LiDAR tile is seen from above), with up from the file where it says (core.io.view_hint: E57
pose, PCD VIEWPOINT, LAS/LAZ and geographic data: z) and otherwise the format's convention:
meshes and scans in graphics formats (PLY, OBJ, OFF, STL, glTF: the Stanford scans among them)
have y up; an E57 scan without a pose says nothing (converters write y-up objects, scanners
z-up rooms): of z and y, the one more across the thinnest axis is up (z on a tie); everything
else is z up (scanners, GIS). When up lies along the look direction (a view from above), the
front direction is up on screen, as in the top preset.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np

from core.io.view_hint import quaternion_matrix

__all__ = ["PRESETS", "Y_UP", "Z_UP", "ViewFrame", "frame_for", "quaternion_matrix",
           "thinnest_axis"]

Y_UP_SUFFIXES = {".ply", ".obj", ".off", ".stl", ".glb", ".gltf"}
PRESETS = ("top", "front", "side", "iso")  # the View menu's
OPENING = "thinnest"  # the preset a dataset opens with when its thinnest axis is known
PCA_SAMPLE = 100_000  # points used to find the principal axes
ALONG = 0.95  # |cos| above which two directions count as the same line
#: The thinnest axis counts only when the points spread along it less than this share of
#: their spread along the next one (a cube has none: it opens with the iso preset).
DISTINCT = 0.9


@dataclass(frozen=True)
class ViewFrame:
    """Up (3,) and front (3,) unit vectors: the front view looks along `front` with `up` up;
    `thin` (3,) the points' thinnest principal axis (None: unknown); `start` is the preset a
    dataset opens with."""

    up: tuple[float, float, float]
    front: tuple[float, float, float]
    start: str = "iso"
    thin: tuple[float, float, float] | None = None

    def direction(self, preset: str) -> tuple[np.ndarray, np.ndarray]:
        """(look direction, view up), unit (3,) float64 each, of a preset in PRESETS or
        OPENING (along the thinnest axis)."""
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
            return _upright(look / np.linalg.norm(look), up, front)
        if preset == OPENING and self.thin is not None:
            return _upright(self._thin_look(), up, front)
        raise ValueError(f"unknown view preset {preset!r}; choose one of {', '.join(PRESETS)}")

    def _thin_look(self) -> np.ndarray:
        """The thinnest axis, signed to look along front where it mostly does (a sensor's
        own side), else downwards (from above, as the other presets)."""
        look = np.asarray(self.thin, dtype=float)
        along_front = float(look @ np.asarray(self.front, dtype=float))
        if abs(along_front) >= 0.5:
            return look if along_front > 0 else -look
        return -look if float(look @ np.asarray(self.up, dtype=float)) > 0 else look


def _upright(look: np.ndarray, up: np.ndarray, front: np.ndarray
             ) -> tuple[np.ndarray, np.ndarray]:
    """(look, view up): up made perpendicular to look; front instead where up lies along
    look (a view from above: the far side is up on screen)."""
    for candidate in (up, front):
        view_up = candidate - (candidate @ look) * look
        if np.linalg.norm(view_up) > np.sqrt(1 - ALONG**2):
            return look, view_up / np.linalg.norm(view_up)
    other = np.roll(look, 1)  # any direction across look
    view_up = other - (other @ look) * look
    return look, view_up / np.linalg.norm(view_up)


Z_UP = ViewFrame(up=(0.0, 0.0, 1.0), front=(0.0, 1.0, 0.0))
Y_UP = ViewFrame(up=(0.0, 1.0, 0.0), front=(0.0, 0.0, -1.0))


def thinnest_axis(points: np.ndarray) -> tuple[float, float, float] | None:
    """(3,) unit direction in which the (n, 3) points spread least (the last right singular
    vector of the centred points, on an even sample of PCA_SAMPLE); None for 2D points, fewer
    than 3 points, no spread, or no distinctly thinnest direction (DISTINCT)."""
    points = np.asarray(points, dtype=np.float64)
    if points.ndim != 2 or points.shape[1] != 3 or len(points) < 3:
        return None
    sample = points[:: max(1, len(points) // PCA_SAMPLE)]
    centred = sample - sample.mean(axis=0)
    _, spread, axes = np.linalg.svd(centred, full_matrices=False)
    if not np.all(np.isfinite(spread)) or spread[0] == 0 or spread[2] >= DISTINCT * spread[1]:
        return None
    return tuple(float(c) for c in axes[-1])


def up_frame(path: Path, report) -> ViewFrame | None:
    """Up and front from the file (report.view, core.io.view_hint), else the format's
    convention (y up for graphics formats, z up for the rest); None for an E57 file that
    says nothing (no pose)."""
    hint = getattr(report, "view", None)
    if hint is not None:
        up = np.asarray(hint.up, dtype=float)
        if hint.front is not None:
            return ViewFrame(up=tuple(hint.up), front=tuple(hint.front), start="front")
        base = Z_UP if abs(up[2]) >= abs(up[1]) else Y_UP
        front = np.asarray(base.front, dtype=float)
        front = front - (front @ up) * up  # across the file's up
        return ViewFrame(up=tuple(hint.up),
                         front=tuple(float(c) for c in front / np.linalg.norm(front)))
    suffix = Path(path).suffix.lower()
    if suffix == ".e57":
        return None
    return Y_UP if suffix in Y_UP_SUFFIXES else Z_UP


def frame_for(path: Path, report, points: np.ndarray | None = None) -> ViewFrame:
    """The view frame of a dataset read from path with this LoadReport (None allowed): up
    from the file or its format; with its (n, 3) `points`, it opens along their thinnest
    axis."""
    frame = up_frame(path, report)
    thin = thinnest_axis(points) if points is not None else None
    if frame is None:  # of z and y, the one more across the thinnest axis
        frame = Y_UP if thin is not None and abs(thin[2]) > abs(thin[1]) else Z_UP
    return frame if thin is None else replace(frame, start=OPENING, thin=thin)

"""Read a point file for the app: the core reader when present, else a plain PLY fallback."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from core.errors import FileFormatError


def read_points(path: str | Path) -> np.ndarray:
    """(n, 2) or (n, 3) float64 points of the file at path; FileFormatError when unreadable."""
    try:
        from core.io import read_points as core_read_points
    except ImportError:
        return read_ply_points(Path(path))
    return np.asarray(core_read_points(path).points, dtype=np.float64)


def read_formats() -> dict[str, str]:
    """Readable file extensions ('.ply' -> description), from core.io when present."""
    try:
        from core.io import READ_FORMATS
    except ImportError:
        return {".ply": "Stanford PLY"}
    return dict(READ_FORMATS)


def read_ply_points(path: Path) -> np.ndarray:
    """(n, 3) float64 x, y, z of a PLY file's vertex element (fallback reader)."""
    from plyfile import PlyData

    try:
        vertex = PlyData.read(str(path))["vertex"]
        points = np.column_stack([vertex[axis] for axis in "xyz"]).astype(np.float64)
    except (OSError, ValueError, KeyError, IndexError) as error:
        raise FileFormatError(f"{path}: not a readable PLY point file ({error})") from error
    return points

"""LAS/LAZ LiDAR via laspy (lazrs backend for LAZ), with scale and offset applied."""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np

from core.errors import FileFormatError
from core.io.las_checks import MAX_LAZ_RATIO, check_las_file


def _open(path: Path):
    """laspy reader object; errors become format errors naming the file."""
    import laspy

    try:
        return laspy.open(str(path))
    except Exception as exc:  # laspy raises LaspyException, ValueError, OSError...
        raise FileFormatError(f"{path}: not a readable LAS/LAZ file ({exc})") from None


def _check_size(header, path: Path) -> None:
    """Refuse point counts the file cannot hold, before laspy allocates for them."""
    size = os.path.getsize(path)
    raw = header.point_count * header.point_format.size
    limit = size * MAX_LAZ_RATIO if header.are_points_compressed else size
    if raw > limit:
        raise FileFormatError(f"{path}: truncated LAS/LAZ (header claims "
                              f"{header.point_count:,} points, file has {size:,} bytes)")


def _colors(las) -> np.ndarray | None:
    """(n, 3) uint8 RGB, or None when the format has no colour or every colour is 0."""
    names = set(las.point_format.dimension_names)
    if not {"red", "green", "blue"}.issubset(names):
        return None
    rgb = np.column_stack([np.asarray(las[c]) for c in ("red", "green", "blue")])
    if not rgb.any():
        return None
    return (rgb >> 8 if rgb.max() > 255 else rgb).astype(np.uint8)


def read_las(path: Path, columns=None) -> tuple[np.ndarray, dict[str, np.ndarray], tuple]:
    """(n, 3) scaled coordinates plus colours, intensity and classification."""
    check_las_file(path)
    with _open(path) as reader:
        _check_size(reader.header, path)
        try:
            las = reader.read()
        except Exception as exc:  # truncated or corrupt point records
            raise FileFormatError(f"{path}: bad LAS/LAZ point data ({exc})") from None
    points = np.column_stack([np.asarray(las.x), np.asarray(las.y), np.asarray(las.z)])
    attrs: dict[str, np.ndarray] = {
        "intensity": np.asarray(las.intensity, dtype=np.float64),
        "classification": np.asarray(las.classification, dtype=np.uint8),
    }
    colors = _colors(las)
    if colors is not None:
        attrs["colors"] = colors
    version = f"LAS {las.header.version}, point format {las.header.point_format.id}"
    return points.astype(np.float64), attrs, (version,)

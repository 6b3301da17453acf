"""LAS/LAZ LiDAR via laspy (lazrs backend for LAZ), with scale and offset applied."""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np

from core.errors import FileFormatError
from core.io.las_checks import MAX_LAZ_RATIO, check_las_file
from core.io.problems import unreadable
from core.io.view_hint import Z_UP_HINT, ViewHint

BOUNDS_RTOL = 0.01  # points beyond the header's box by this fraction of its size are reported


def _open(path: Path):
    """laspy reader object; errors become format errors naming the file."""
    import laspy

    try:
        return laspy.open(str(path))
    except Exception as exc:  # laspy raises LaspyException, ValueError, OSError...
        raise unreadable(path, "LAS/LAZ", exc) from exc


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
            raise unreadable(path, "LAS/LAZ", exc) from exc
    points = np.column_stack([np.asarray(las.x), np.asarray(las.y), np.asarray(las.z)])
    attrs: dict[str, np.ndarray] = {
        "intensity": np.asarray(las.intensity, dtype=np.float64),
        "classification": np.asarray(las.classification, dtype=np.uint8),
    }
    colors = _colors(las)
    if colors is not None:
        attrs["colors"] = colors
    version = f"LAS {las.header.version}, point format {las.header.point_format.id}"
    points = points.astype(np.float64)
    notes = (version, *outside_bounds(points, las.header), *crs_mismatch(points, las.header),
             ViewHint(up=Z_UP_HINT, front=None, source="LiDAR (LAS/LAZ): z up"))
    return points, attrs, notes


def outside_bounds(points: np.ndarray, header) -> tuple[str, ...]:
    """A warning when points lie well outside the header's declared bounding box.

    The file's problem (a corrupt record, scale or offset), not ours: the points are kept,
    and the report says so. Header boxes left at zero by some writers are not checked.
    """
    lo, hi = np.asarray(header.mins, dtype=np.float64), np.asarray(header.maxs, dtype=np.float64)
    if not (np.isfinite(lo).all() and np.isfinite(hi).all()) or not (lo.any() or hi.any()):
        return ()
    tol = np.maximum(BOUNDS_RTOL * (hi - lo), 2.0 * np.abs(np.asarray(header.scales)))
    with np.errstate(invalid="ignore"):
        below, above = lo - tol - points, points - hi - tol
    out = np.nanmax(np.maximum(below, above), axis=1, initial=0.0) > 0
    if not out.any():
        return ()
    far = float(np.nanmax(np.maximum(below, above)[out]))
    return (f"warning: {int(out.sum()):,} points lie outside the header's bounding box "
            f"(by up to {far:.6g}): corrupt records, scale or offset?",)


def crs_mismatch(points: np.ndarray, header) -> tuple[str, ...]:
    """A warning when the file declares a geographic CRS but holds coordinates that cannot
    be degrees (a wrong CRS record; the coordinates are read as they are)."""
    try:
        crs = header.parse_crs()
    except Exception:  # pyproj or laspy refusing a malformed CRS record
        return ("warning: the CRS record cannot be parsed",)
    if crs is None or not crs.is_geographic:
        return ()
    with np.errstate(invalid="ignore"):
        big = np.nanmax(np.abs(points[:, :2]), axis=0, initial=0.0)
    if big[0] <= 360.0 and big[1] <= 90.0:
        return ()
    return (f"warning: the file declares the geographic CRS {crs.name!r} (degrees) but its x, y "
            f"reach {max(big):,.6g}: not degrees; read as plain coordinates",)

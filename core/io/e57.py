"""E57 (ASTM E2807) scans via pye57: every scan (or one), poses applied, Cartesian or spherical
coordinates, invalid points dropped, intensity and colour (scaled by the file's limits) kept."""

from __future__ import annotations

import contextlib
import os
import tempfile
from pathlib import Path

import numpy as np

from core.errors import FileFormatError
from core.io.problems import unreadable
from core.io.report import Skipped
from core.io.sizes import check_memory
from core.io.view_hint import pose_hint

CARTESIAN = ("cartesianX", "cartesianY", "cartesianZ")
SPHERICAL = ("sphericalRange", "sphericalAzimuth", "sphericalElevation")
COLOURS = ("colorRed", "colorGreen", "colorBlue")
BOUNDS_RTOL = 1e-6  # points may pass the declared bounds by this share of their size (rounding)


def _open(path: Path, stack: contextlib.ExitStack):
    """The pye57 reader, or a clear error when the file (or the library) is missing or bad.
    A file name that is not UTF-8 (the library takes only UTF-8 text) is opened through a
    link of a plain name in a temporary folder, which `stack` removes."""
    try:
        import pye57
    except ImportError:  # pragma: no cover - pye57 is a dependency; a broken install says so
        raise FileFormatError(f"{path}: reading E57 needs the 'pye57' package "
                              "(pip install pye57)") from None
    name = str(path)
    try:
        name.encode("utf-8")
    except UnicodeEncodeError:  # undecodable bytes of the name, kept as surrogates
        folder = Path(stack.enter_context(tempfile.TemporaryDirectory(prefix="alphascoop-")))
        link = folder / "scan.e57"
        try:
            os.symlink(os.path.abspath(os.fsencode(path)), os.fsencode(link))
        except OSError as exc:
            raise unreadable(path, "E57", exc) from exc
        name = str(link)
    try:
        return pye57.E57(name)
    except Exception as exc:  # libE57Format raises its own exception types
        raise unreadable(path, "E57", exc) from exc


def spherical_to_cartesian(rae: np.ndarray) -> np.ndarray:
    """(n, 3) xyz from (n, 3) range, azimuth, elevation (radians), as ASTM E2807 defines."""
    r, azimuth, elevation = rae.T
    flat = r * np.cos(elevation)
    return np.column_stack([flat * np.cos(azimuth), flat * np.sin(azimuth), r * np.sin(elevation)])


FLAG_FIELDS = ("cartesianInvalidState", "sphericalInvalidState")  # 0 valid, 1-2 invalid
#: Why a record with an invalid state is left out (ASTM E2807: 1 = only the direction is
#: meaningful, 2 = nothing is).
INVALID_REASONS = {1: "have no range (direction only)", 2: "are flagged invalid"}


def _read_fields(e57, header, names: list[str], path: Path) -> dict[str, np.ndarray]:
    """The named point fields of a scan, scaled, as float64 (flags as int8, as pye57 does:
    64-bit integer buffers gave wrong flags for half the points of a real file)."""
    from pye57 import libe57

    n = header.point_count
    check_memory(path, n * 8 * len(names), f"a scan of {n:,} points")  # bit-packed data
    arrays, buffers = {}, libe57.VectorSourceDestBuffer()
    for name in names:
        arrays[name] = np.empty(n, dtype=np.int8 if name in FLAG_FIELDS else np.float64)
        buffers.append(libe57.SourceDestBuffer(e57.image_file, name, arrays[name], n, True, True))
    reader = header.points.reader(buffers)
    try:
        got = reader.read()
    finally:
        reader.close()
    return {k: v[:got] for k, v in arrays.items()}


def _colour_range(header, name: str) -> tuple[float, float]:
    """A colour channel's limits: the scan's colorLimits, else the prototype's bounds."""
    from pye57 import libe57
    from pye57.utils import get_node

    node = header.node
    if node.isDefined("colorLimits") and node["colorLimits"].isDefined(name + "Maximum"):
        box = node["colorLimits"]
        return float(box[name + "Minimum"].value()), float(box[name + "Maximum"].value())
    field = get_node(libe57.StructureNode(header.points.prototype()), name)
    return float(field.minimum()), float(field.maximum())


def _colours(header, raw: dict) -> np.ndarray:
    """(n, 3) uint8 colours scaled from the channel limits to 0..255."""
    out = []
    for name in COLOURS:
        lo, hi = _colour_range(header, name)
        span = hi - lo if hi > lo else 1.0
        out.append(np.clip((raw[name] - lo) * (255.0 / span), 0, 255).round())
    return np.column_stack(out).astype(np.uint8)


def _scan(e57, index: int, path: Path) -> tuple:
    """(valid points with the scan's pose applied, attributes, (3,) int64 records in each
    invalid state 0..2 (0: none left out), the pose's ViewHint or None) of one scan."""
    header = e57.get_header(index)
    fields = set(header.point_fields)
    system = CARTESIAN if fields.issuperset(CARTESIAN) else SPHERICAL
    if not fields.issuperset(system):
        raise FileFormatError(f"{path}: E57 scan {index} has neither Cartesian nor spherical "
                              f"coordinates ({', '.join(sorted(fields))})")
    state = "cartesianInvalidState" if system == CARTESIAN else "sphericalInvalidState"
    extra = [f for f in (state, "intensity", *COLOURS) if f in fields]
    raw = _read_fields(e57, header, [*system, *extra], path)
    local = np.column_stack([raw[f] for f in system])
    if system == SPHERICAL:
        local = spherical_to_cartesian(local)
    flags = raw[state] if state in raw else np.zeros(len(local), dtype=np.int8)
    valid = flags == 0
    invalid = np.bincount(np.clip(flags[~valid], 1, 2), minlength=3)
    points = local @ header.rotation_matrix.T + header.translation if header.has_pose() else local
    if system == CARTESIAN:
        check_bounds(header, local[valid], points[valid], index, path)
    attrs = {}
    if "intensity" in raw:
        attrs["intensity"] = raw["intensity"]
    if fields.issuperset(COLOURS):
        attrs["colors"] = _colours(header, raw)
    hint = pose_hint(header.rotation_matrix) if header.has_pose() else None
    return points[valid], {k: v[valid] for k, v in attrs.items()}, invalid, hint


def declared_bounds(header) -> np.ndarray | None:
    """(2, 3) [min, max] of x, y, z that the scan's header declares (cartesianBounds), None
    when it declares none (or not all six, or not finite)."""
    node = header.node
    if not node.isDefined("cartesianBounds"):
        return None
    box = node["cartesianBounds"]
    names = [f"{axis}{end}" for end in ("Minimum", "Maximum") for axis in "xyz"]
    if not all(box.isDefined(name) for name in names):
        return None
    try:
        bounds = np.array([float(box[name].value()) for name in names]).reshape(2, 3)
    except (TypeError, ValueError):
        return None
    return bounds if bool(np.isfinite(bounds).all()) else None


def check_bounds(header, local: np.ndarray, posed: np.ndarray, index: int, path: Path) -> None:
    """FileFormatError when valid points lie outside the bounds the scan declares: the
    library read a damaged file as points that are not the scan's. Writers give the bounds
    before the pose (as ASTM E2807 says), after it, or (pye57) as the two corners moved by
    the pose: points inside any of these boxes pass."""
    bounds = declared_bounds(header)
    if bounds is None or len(local) == 0:
        return
    boxes = [(local, bounds), (posed, bounds)]
    if header.has_pose():  # the corners moved back: the local box they came from
        corners = (bounds - header.translation) @ header.rotation_matrix
        boxes.append((local, corners))
    slack = BOUNDS_RTOL * max(float(np.abs(bounds).max()), 1.0)
    outside = [np.any((pts < box.min(axis=0) - slack) | (pts > box.max(axis=0) + slack), axis=1)
               for pts, box in boxes]
    bad = min(outside, key=lambda flags: int(flags.sum()))
    if not bad.any():
        return
    first = local[np.argmax(bad)]
    box = ", ".join(f"{a} {lo:.6g}..{hi:.6g}" for a, lo, hi in zip("xyz", *bounds, strict=True))
    raise FileFormatError(
        f"{path}: E57 scan {index} is damaged: {int(bad.sum()):,} of {len(local):,} points lie "
        f"outside the bounds the file declares ({box}), e.g. "
        f"({', '.join(f'{v:.6g}' for v in first)})")


def read_e57(path: Path, columns=None, *, scan: int | None = None) -> tuple:
    """(n, 3) points of every scan (or scan number `scan`), attributes and notes."""
    stack = contextlib.ExitStack()
    try:
        e57 = _open(path, stack)
    except BaseException:
        stack.close()
        raise
    try:
        count = e57.scan_count
        if count == 0:
            raise FileFormatError(f"{path}: E57 file holds no scans")
        if scan is not None and not 0 <= scan < count:
            raise FileFormatError(f"{path}: no scan {scan}; the file has scans 0..{count - 1}")
        chosen = range(count) if scan is None else [scan]
        parts = [_scan(e57, i, path) for i in chosen]
    except FileFormatError:
        raise
    except Exception as exc:  # libE57Format: corrupt pages, bad prototypes...
        raise unreadable(path, "E57", exc) from exc
    finally:
        e57.close()
        stack.close()
    points = np.concatenate([p[0] for p in parts])
    shared = set.intersection(*(set(p[1]) for p in parts))
    attrs = {k: np.concatenate([p[1][k] for p in parts]) for k in sorted(shared)}
    label = f"scan {scan} of {count}" if scan is not None else f"{count} scan(s), poses applied"
    notes = [f"E57: {label}"]
    invalid = sum(p[2] for p in parts)
    skipped = [Skipped(int(invalid[state]), reason) for state, reason in INVALID_REASONS.items()
               if invalid[state]]
    hints = [p[3] for p in parts if p[3] is not None][:1]  # the first scan with a pose
    return points, attrs, (*notes, *skipped, *hints)

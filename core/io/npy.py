"""NumPy arrays (.npy, .npz): plain (n, 2|3+) arrays or structured arrays with x/y/z fields."""

from __future__ import annotations

import zipfile
from pathlib import Path

import numpy as np

from core.errors import FileFormatError
from core.io.columns import clean_name, explicit_columns
from core.io.problems import unreadable
from core.io.sizes import check_npy, check_npz_archive

POINT_KEYS = ("points", "xyz", "coords", "coordinates", "positions", "vertices")
ATTRIBUTE_KEYS = {"normals": "normals", "colors": "colors", "colours": "colors",
                  "weights": "weights", "radius": "radius", "radii": "radius"}


def _from_array(arr: np.ndarray, path: Path, columns=None) -> tuple[np.ndarray, tuple]:
    """(n, d) float64 coordinates from a plain or structured array (`columns` picks 2 or 3),
    and notes. A (2, n) or (3, n) array with more than 3 columns holds one coordinate per
    row: it is read transposed, and the note says so."""
    if arr.dtype.names:
        return _from_fields(arr, path, columns), ()
    if arr.ndim != 2 or arr.shape[1] < 2:
        raise FileFormatError(f"{path}: expected an (n, 2) or (n, 3) array, got shape {arr.shape}")
    if not np.issubdtype(arr.dtype, np.number) or np.iscomplexobj(arr):
        raise FileFormatError(f"{path}: array of {arr.dtype} is not real numbers")
    notes: tuple = ()
    if arr.shape[0] in (2, 3) and arr.shape[1] > 3:
        notes = (f"array of shape {arr.shape} read as {arr.shape[1]:,} points of "
                 f"{arr.shape[0]} coordinates (one coordinate per row: transposed)",)
        arr = arr.T
    if columns is not None:
        picked = arr[:, explicit_columns(columns, None, arr.shape[1], str(path))]
        return picked.astype(np.float64), notes
    return arr[:, : min(arr.shape[1], 3)].astype(np.float64), notes


def _from_fields(arr: np.ndarray, path: Path, columns) -> np.ndarray:
    """Coordinates from the x/y(/z) fields of a structured array, or the `columns` named."""
    arr, fields = arr.reshape(-1), list(arr.dtype.names)
    if columns is not None:
        names = [clean_name(f) for f in fields]
        axes = [fields[i] for i in explicit_columns(columns, names, len(fields), str(path))]
    else:
        axes = [a for a in ("x", "y", "z") if a in fields]
        if axes[:2] != ["x", "y"]:
            raise FileFormatError(f"{path}: structured array without x/y fields")
    if any(not np.issubdtype(arr.dtype[a], np.number) for a in axes):
        raise FileFormatError(f"{path}: fields {', '.join(axes)} are not all numbers")
    return np.column_stack([arr[a] for a in axes]).astype(np.float64)


def read_npy(path: Path, columns=None, extra: tuple[str, ...] = ()
             ) -> tuple[np.ndarray, dict[str, np.ndarray], tuple]:
    """Points (and for .npz any normals/colors/weights/radius arrays of matching length, and
    the arrays named in `extra` under their own names)."""
    with open(path, "rb") as fh:  # our handle: np.load leaks its own when a zip is broken
        try:
            if path.suffix.lower() == ".npy":
                check_npy(path, fh)
            data = np.load(fh, allow_pickle=False)
            if isinstance(data, np.ndarray):
                points, notes = _from_array(data, path, columns)
                return points, {}, notes
            return _from_archive(data, path, columns, extra)
        except FileFormatError:  # already says what is wrong (it is also a ValueError)
            raise
        except (ValueError, OSError, EOFError, KeyError, zipfile.BadZipFile) as exc:
            raise unreadable(path, "NumPy", exc) from exc


def _from_archive(data, path: Path, columns, extra: tuple[str, ...] = ()
                  ) -> tuple[np.ndarray, dict[str, np.ndarray], tuple]:
    """Points and attributes from an open NpzFile."""
    keys = list(data.files)
    key = next((k for k in POINT_KEYS if k in keys), keys[0] if len(keys) == 1 else None)
    if key is None:
        raise FileFormatError(f"{path}: no points array (looked for {', '.join(POINT_KEYS)};"
                              f" found {', '.join(keys) or 'nothing'})")
    read = [key, *(k for k in keys if k in ATTRIBUTE_KEYS or k in extra)]
    check_npz_archive(path, data.zip, read)
    points, notes = _from_array(data[key], path, columns)
    attrs = {ATTRIBUTE_KEYS[k]: data[k] for k in keys if k in ATTRIBUTE_KEYS}
    attrs.update({k: data[k] for k in extra if k in keys})
    if notes:  # attributes stored the same way, one value per column
        attrs = {k: v.T if v.ndim == 2 and v.shape[0] == points.shape[1] and v.shape[1] == len(
            points) else v for k, v in attrs.items()}
    attrs = {k: v for k, v in attrs.items() if len(v) == len(points)}
    return points, attrs, (f"points from array {key!r}", *notes)

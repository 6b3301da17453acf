"""NumPy arrays (.npy, .npz): plain (n, 2|3+) arrays or structured arrays with x/y/z fields."""

from __future__ import annotations

import zipfile
from pathlib import Path

import numpy as np

from core.errors import FileFormatError

POINT_KEYS = ("points", "xyz", "coords", "coordinates", "positions", "vertices")
ATTRIBUTE_KEYS = {"normals": "normals", "colors": "colors", "colours": "colors",
                  "weights": "weights"}


def _from_array(arr: np.ndarray, path: Path, columns=None) -> np.ndarray:
    """(n, d) float64 coordinates from a plain or structured array."""
    if arr.dtype.names:
        axes = [a for a in ("x", "y", "z") if a in arr.dtype.names]
        if axes[:2] != ["x", "y"]:
            raise FileFormatError(f"{path}: structured array without x/y fields")
        return np.column_stack([arr[a] for a in axes]).astype(np.float64)
    if arr.ndim != 2 or arr.shape[1] < 2:
        raise FileFormatError(f"{path}: expected an (n, 2) or (n, 3) array, got shape {arr.shape}")
    if not np.issubdtype(arr.dtype, np.number) or np.iscomplexobj(arr):
        raise FileFormatError(f"{path}: array of {arr.dtype} is not real numbers")
    cols = [int(c) for c in str(columns).split(",")] if columns is not None else None
    if cols is not None:
        if any(not -arr.shape[1] <= c < arr.shape[1] for c in cols):
            raise FileFormatError(f"{path}: columns {cols} out of range for shape {arr.shape}")
        return arr[:, cols].astype(np.float64)
    return arr[:, : min(arr.shape[1], 3)].astype(np.float64)


def read_npy(path: Path, columns=None) -> tuple[np.ndarray, dict[str, np.ndarray], tuple]:
    """Points (and for .npz any normals/colors/weights arrays of matching length)."""
    with open(path, "rb") as fh:  # our handle: np.load leaks its own when a zip is broken
        try:
            data = np.load(fh, allow_pickle=False)
            if isinstance(data, np.ndarray):
                return _from_array(data, path, columns), {}, ()
            return _from_archive(data, path, columns)
        except (ValueError, OSError, EOFError, KeyError, zipfile.BadZipFile) as exc:
            raise FileFormatError(f"{path}: not a readable NumPy file ({exc})") from None


def _from_archive(data, path: Path, columns) -> tuple[np.ndarray, dict[str, np.ndarray], tuple]:
    """Points and attributes from an open NpzFile."""
    keys = list(data.files)
    key = next((k for k in POINT_KEYS if k in keys), keys[0] if len(keys) == 1 else None)
    if key is None:
        raise FileFormatError(f"{path}: no points array (looked for {', '.join(POINT_KEYS)};"
                              f" found {', '.join(keys) or 'nothing'})")
    points = _from_array(data[key], path, columns)
    attrs = {ATTRIBUTE_KEYS[k]: data[k] for k in keys if k in ATTRIBUTE_KEYS}
    attrs = {k: v for k, v in attrs.items() if len(v) == len(points)}
    return points, attrs, (f"points from array {key!r}",)

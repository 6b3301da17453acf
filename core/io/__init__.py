"""Read point sets from scan, mesh and table files into a PointSet with a load report."""

from __future__ import annotations

import os
import warnings
from collections.abc import Callable, Sequence
from pathlib import Path

import numpy as np

from core.errors import FileFormatError
from core.georef import Georef
from core.io.columns import parse_columns
from core.io.geographic import geographic_points
from core.io.las import read_las
from core.io.mesh import read_mesh
from core.io.npy import read_npy
from core.io.pcd import read_pcd
from core.io.ply import read_ply
from core.io.report import LoadReport, PointSet, finish
from core.io.subsample import SUBSAMPLE_METHODS
from core.io.text import read_text, read_text_columns

__all__ = ["READ_FORMATS", "SUBSAMPLE_METHODS", "LoadReport", "PointSet", "read_points"]

READ_FORMATS: dict[str, str] = {
    ".ply": "PLY polygon/point file (ascii or binary)",
    ".xyz": "XYZ text points",
    ".pts": "PTS text points (Leica)",
    ".txt": "Text table of points",
    ".csv": "CSV table (named or first numeric columns)",
    ".pcd": "PCD point cloud (PCL)",
    ".las": "LAS LiDAR",
    ".laz": "LAZ compressed LiDAR",
    ".npy": "NumPy array",
    ".npz": "NumPy archive",
    ".obj": "Wavefront OBJ mesh (vertices)",
    ".stl": "STL mesh, ascii or binary (vertices)",
    ".off": "OFF mesh (vertices)",
    ".glb": "glTF binary mesh (vertices)",
    ".gltf": "glTF mesh (vertices)",
    ".vtk": "Legacy VTK (vertices)",
    ".vtu": "VTK unstructured grid (vertices)",
}

Reader = Callable[[Path, object], tuple[np.ndarray, dict[str, np.ndarray], tuple]]
READERS: dict[str, Reader] = {
    ".ply": read_ply, ".pcd": read_pcd, ".las": read_las, ".laz": read_las,
    ".npy": read_npy, ".npz": read_npy,
    **dict.fromkeys((".xyz", ".pts", ".txt", ".csv"), read_text),
    **dict.fromkeys((".obj", ".stl", ".off", ".glb", ".gltf", ".vtk", ".vtu"), read_mesh),
}


def _format_name(ext: str) -> str:
    """Short format label for reports: 'PLY', 'LAZ'..."""
    return ext.lstrip(".").upper()


def _check_file(path: Path) -> str:
    """The lower-case extension of a readable, non-empty file, or a clear error."""
    ext = path.suffix.lower()
    if ext not in READERS:
        known = " ".join(sorted(READERS))
        raise FileFormatError(f"{path}: unknown extension {ext or '(none)'!r}; known: {known}")
    if not path.is_file():
        raise FileFormatError(f"{path}: no such file")
    if os.path.getsize(path) == 0:
        raise FileFormatError(f"{path}: empty file")
    return ext


def read_points(
    path: str | os.PathLike,
    *,
    columns: str | Sequence[str | int] | None = None,
    subsample: int | None = None,
    seed: int = 0,
    subsample_method: str = "voxel",
) -> PointSet:
    """Read a point file by extension; non-finite rows dropped, duplicates merged, reported.

    `columns` picks coordinate columns ('lon,lat' or [0, 1, 2]) in text and NumPy files;
    `subsample` thins to at most that many points ('voxel' grid or 'random', seeded).
    Every failure is a FileFormatError whose message names the file and the problem.
    """
    path = Path(path)
    ext = _check_file(path)
    with np.errstate(all="ignore"), warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        points, attrs, notes, georef = _read(path, ext, columns)
        if points.ndim != 2 or points.shape[1] not in (2, 3):
            raise FileFormatError(f"{path}: points must have 2 or 3 coordinates, "
                                  f"got shape {points.shape}")
        ps = finish(path, _format_name(ext), points, attrs, subsample=subsample,
                    method=subsample_method, seed=seed, georef=georef,
                    notes=tuple(notes) + _warning_notes(caught))
    if len(ps.points) == 0:
        raise FileFormatError(f"{path}: no finite points ({ps.report.n_read:,} rows read)")
    return ps


def _warning_notes(caught: list[warnings.WarningMessage]) -> tuple[str, ...]:
    """Library warnings met while reading, as report notes (numeric ones are counted anyway)."""
    seen = dict.fromkeys(str(w.message).splitlines()[0][:120] for w in caught
                         if not issubclass(w.category, RuntimeWarning) and str(w.message))
    return tuple(f"reader warning: {m}" for m in list(seen)[:3])


def _read(path: Path, ext: str, columns) -> tuple[np.ndarray, dict[str, np.ndarray], tuple,
                                                  Georef | None]:
    """(points, attributes, notes, georef): named longitude/latitude columns of text files
    projected to metres (core.io.geographic), the other formats' points as they are."""
    if READERS[ext] is read_text:
        points, attrs, notes, names = _reported(path, ext, read_text_columns, columns)
        if names is None or _by_index(columns):
            return points, attrs, notes, None
        points, attrs, more, georef = geographic_points(points, attrs, names,
                                                        explicit=columns is not None)
        return points, attrs, tuple(notes) + more, georef
    return (*_reported(path, ext, READERS[ext], columns), None)


def _by_index(columns) -> bool:
    """True when `columns` picks every column by its index (plain numbers, never projected)."""
    return columns is not None and all(isinstance(c, int) for c in parse_columns(columns))


def _reported(path: Path, ext: str, reader, columns) -> tuple:
    """reader(path, columns), with every failure as a FileFormatError naming the file."""
    try:
        return reader(path, columns)
    except MemoryError:
        raise FileFormatError(f"{path}: too large to read into memory") from None
    except (OSError, UnicodeDecodeError) as exc:
        raise FileFormatError(f"{path}: cannot read ({exc})") from None
    except FileFormatError:
        raise
    except BaseException as exc:  # a third-party parser choking on a corrupt file
        if not isinstance(exc, Exception) and type(exc).__name__ != "PanicException":
            raise  # KeyboardInterrupt, SystemExit...; Rust panics (lazrs) are BaseExceptions
        raise FileFormatError(f"{path}: unreadable {_format_name(ext)} file "
                              f"({type(exc).__name__}: {exc})") from exc

"""Read point sets from scan, mesh, molecule and table files into a PointSet with a load
report: `read_points` picks the reader by extension (the README's format table)."""

from __future__ import annotations

import functools
import os
import warnings
from collections.abc import Callable, Sequence
from pathlib import Path

import numpy as np

from core.errors import FileFormatError
from core.geometry.georef import Georef
from core.io.columns import clean_name, parse_columns
from core.io.e57 import read_e57
from core.io.geographic import geographic_points
from core.io.las import read_las
from core.io.mesh import read_mesh
from core.io.molecule import molecule_extension, read_molecule_points
from core.io.npy import read_npy
from core.io.pcd import read_pcd
from core.io.ply import read_ply
from core.io.precheck import precheck
from core.io.problems import plain_line, unreadable
from core.io.report import LoadReport, PointSet, Skipped, finish
from core.io.subsample import SUBSAMPLE_METHODS
from core.io.text import read_text, read_text_columns
from core.io.view_hint import Z_UP_HINT, ViewHint
from core.io.weighting import choose_weights

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
    ".pdb": "PDB molecule (atoms; also .ent and .gz)",
    ".cif": "mmCIF molecule (atoms; also .mmcif and .gz)",
    ".pqr": "PQR molecule (atoms with their radii, PDB2PQR)",
    ".xyzr": "XYZR atoms: x y z radius per line (MSMS)",
    ".e57": "E57 terrestrial scans (ASTM E2807), every scan with its pose",
}

Reader = Callable[[Path, object], tuple[np.ndarray, dict[str, np.ndarray], tuple]]
READERS: dict[str, Reader] = {
    ".ply": read_ply, ".pcd": read_pcd, ".las": read_las, ".laz": read_las,
    ".npy": read_npy, ".npz": read_npy,
    **dict.fromkeys((".xyz", ".pts", ".txt", ".csv"), read_text),
    **dict.fromkeys((".obj", ".stl", ".off", ".glb", ".gltf", ".vtk", ".vtu"), read_mesh),
    **dict.fromkeys((".pdb", ".ent", ".cif", ".mmcif", ".pqr", ".xyzr"), read_molecule_points),
    ".e57": read_e57,
}


def _format_name(ext: str) -> str:
    """Short format label for reports: 'PLY', 'LAZ'..."""
    return ext.lstrip(".").upper()


def _check_file(path: Path) -> str:
    """The lower-case extension of a readable, non-empty file, or a clear error."""
    ext = molecule_extension(path) or path.suffix.lower()
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
    weights: str | None = None,
    radius: str | None = None,
    radius_add: float | None = None,
    scan: int | None = None,
) -> PointSet:
    """Read a point file by extension; non-finite rows dropped, duplicates merged, reported.

    `columns` picks coordinate columns ('lon,lat' or [0, 1, 2]) in text and NumPy files;
    `subsample` thins to at most that many points ('voxel' grid or 'random', seeded).
    Weights (squared radii, `PointSet.weights`) come from a weight column (weight, w) or a
    radius column (radius, r: squared), found by name or named by `weights` / `radius`;
    `radius_add` adds a probe radius to every radius first. `scan` reads only that scan
    (0-based) of an E57 file instead of all of them.
    Every failure is a FileFormatError whose message names the file and the problem.
    """
    path = Path(path)
    ext = _check_file(path)
    if scan is not None and ext != ".e57":
        raise FileFormatError(f"{path}: choosing a scan applies to E57 files only")
    extra = tuple(clean_name(c) for c in (weights, radius) if c is not None)
    with np.errstate(all="ignore"), warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        points, attrs, notes, georef = _read(path, ext, columns, extra, scan)
        if points.ndim != 2 or points.shape[1] not in (2, 3):
            raise FileFormatError(f"{path}: points must have 2 or 3 coordinates, "
                                  f"got shape {points.shape}")
        attrs, source = choose_weights(attrs, path, weights=weights, radius=radius,
                                       radius_add=radius_add)
        skipped = tuple(n for n in notes if isinstance(n, Skipped))
        view = next((n for n in notes if isinstance(n, ViewHint)), None)
        if view is None and georef is not None:  # projected from longitude/latitude
            view = ViewHint(up=Z_UP_HINT, front=None, source="geographic: z up")
        notes = tuple(n for n in notes if isinstance(n, str))
        ps = finish(path, _format_name(ext), points, attrs, subsample=subsample,
                    method=subsample_method, seed=seed, georef=georef,
                    notes=notes + _warning_notes(caught), weights_from=source,
                    skipped=skipped, view=view)
    if len(ps.points) == 0:
        raise FileFormatError(f"{path}: no finite points ({ps.report.n_read:,} rows read)")
    return ps


def _warning_notes(caught: list[warnings.WarningMessage]) -> tuple[str, ...]:
    """Library warnings met while reading, as report notes (numeric ones are counted anyway)."""
    seen = dict.fromkeys(str(w.message).splitlines()[0][:120] for w in caught
                         if not issubclass(w.category, RuntimeWarning) and str(w.message))
    return tuple(f"reader warning: {m}" for m in list(seen)[:3])


def _read(path: Path, ext: str, columns, extra: tuple[str, ...] = (), scan: int | None = None
          ) -> tuple[np.ndarray, dict[str, np.ndarray], tuple, Georef | None]:
    """(points, attributes, notes, georef): named longitude/latitude columns of text files
    projected to metres (core.io.geographic), the other formats' points as they are.
    `extra` names columns (text) or arrays (.npz) to read as attributes too; `scan` picks one
    scan of an E57 file."""
    if READERS[ext] is read_text:
        reader = functools.partial(read_text_columns, extra=extra)
        points, attrs, notes, names = _reported(path, ext, reader, columns)
        if names is None or _by_index(columns):
            return points, attrs, notes, None
        points, attrs, more, georef = geographic_points(points, attrs, names,
                                                        explicit=columns is not None,
                                                        source=str(path))
        return points, attrs, tuple(notes) + more, georef
    if ext == ".e57":
        reader = functools.partial(read_e57, scan=scan)
    elif READERS[ext] is read_npy:
        reader = functools.partial(read_npy, extra=extra)
    else:
        reader = READERS[ext]
    return (*_reported(path, ext, reader, columns), None)


def _by_index(columns) -> bool:
    """True when `columns` picks every column by its index (plain numbers, never projected)."""
    return columns is not None and all(isinstance(c, int) for c in parse_columns(columns))


def _reported(path: Path, ext: str, reader, columns) -> tuple:
    """reader(path, columns), with every failure as a FileFormatError naming the file."""
    try:
        precheck(path, ext)
        return reader(path, columns)
    except MemoryError:
        raise FileFormatError(f"{path}: too large to read into memory") from None
    except OSError as exc:
        if exc.errno is None:  # raised by a parser (trimesh: a 'file' its JSON names), not the OS
            raise unreadable(path, _format_name(ext), exc) from exc
        raise _os_problem(path, exc) from exc
    except FileFormatError as exc:
        raise FileFormatError(plain_line(str(exc))) from exc.__cause__
    except BaseException as exc:  # a third-party parser choking on a corrupt file
        if not isinstance(exc, Exception) and type(exc).__name__ != "PanicException":
            raise  # KeyboardInterrupt, SystemExit...; Rust panics (lazrs) are BaseExceptions
        raise unreadable(path, _format_name(ext), exc) from exc


def _os_problem(path: Path, exc: OSError) -> FileFormatError:
    """An OS error while reading `path` (or a file it refers to, as glTF buffers), in words."""
    other = exc.filename is not None and Path(str(exc.filename)).name != path.name
    reason = exc.strerror or "it cannot be opened"
    if other:
        return FileFormatError(plain_line(f"{path}: the file it refers to, "
                                          f"{Path(str(exc.filename)).name!r}, cannot be read "
                                          f"({reason.lower()})"))
    return FileFormatError(f"{path}: cannot read the file ({reason.lower()})")

"""Write a chosen alpha shape (or the whole interval table) to files other tools read.

Every write is atomic: a temporary file beside the target, renamed over it only on success.
Writers take an optional `progress(fraction, stage)`; raising core.errors.Cancelled from it
stops the write, and the target (or the file already there) is left as it was.
"""

from __future__ import annotations

import contextlib
import os
from collections.abc import Iterator
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from core.errors import AlphaScoopError, FileFormatError
from core.export.complex_vtu import write_vtu
from core.export.geographic import write_prj
from core.export.metadata import shape_metadata, sidecar_text
from core.export.polygons import POLYGON_WRITERS, geographic_metadata
from core.export.surface import SURFACE_WRITERS, manifold_meta, split_listing, surface_arrays
from core.export.table import TABLE_WRITERS
from core.export.targets import refuse_source
from core.geometry.georef import Georef
from core.progress import Progress
from core.storage.atomic import atomic_path, atomic_write_text

__all__ = ["SHAPE_FORMATS", "TABLE_FORMATS", "ExportReport", "write_shape", "write_table"]

SHAPE_FORMATS: dict[str, str] = {
    ".ply": "PLY surface (binary, metadata in comments)",
    ".stl": "STL surface (binary)",
    ".obj": "Wavefront OBJ surface",
    ".off": "OFF surface",
    ".vtp": "VTK PolyData surface",
    ".glb": "glTF binary surface",
    ".gltf": "glTF surface (embedded buffer)",
    ".vtu": "VTK unstructured grid: cells and boundary simplices with class and intervals",
    ".geojson": "GeoJSON polygons with holes (2D)",
    ".wkt": "WKT MultiPolygon (2D)",
    ".svg": "SVG figure (2D)",
    ".csv": "CSV of boundary rings (2D)",
}
TABLE_FORMATS: dict[str, str] = {".npz": "interval table, NumPy archive",
                                 ".csv": "interval table, CSV"}


@dataclass(frozen=True)
class ExportReport:
    """What was written: file, format, counts, measure, closedness and any manifold split."""

    path: str
    format: str
    alpha: float | None
    n_vertices: int = 0
    n_faces: int = 0
    measure: float = 0.0
    closed: bool | None = None
    manifold: str | None = None
    sidecar: str | None = None
    metadata: dict = field(default_factory=dict)
    crs_file: str | None = None
    split_file: str | None = None  # the points a manifold split wrote twice or more (CSV)
    split_points: int = 0

    def line(self) -> str:
        """One-line summary for the CLI and the status bar (units for geographic input)."""
        if self.alpha is None:
            return f"wrote {self.path} (interval table, {self.n_faces:,} simplices)"
        metres = self.metadata.get("units") == "m"
        at = (f"alpha² {self.metadata['alpha2']:.6g}" if self.metadata.get("weighted")
              else f"alpha {self.alpha:.6g}{' m' * metres}")
        parts = [f"wrote {self.path} ({self.format}, {at}"]
        if self.n_faces:
            parts.append(f", {self.n_vertices:,} vertices, {self.n_faces:,} faces")
        label = next((k for k in ("volume", "area") if k in self.metadata), "measure")
        if "area_m2" in self.metadata:  # geographic 2D: measured on the ellipsoid
            parts.append(f", area {self.metadata['area_m2']:.6g} m², perimeter "
                         f"{self.metadata['perimeter_m']:.6g} m on the WGS 84 ellipsoid)")
        else:
            unit = {"volume": " m³", "area": " m²"}.get(label, "") if metres else ""
            parts.append(f", {label} {self.measure:.6g}{unit})")
        if self.crs_file:
            parts.append(f"; longitude/latitude, CRS in {self.crs_file}")
        if self.manifold:
            parts.append(f"; {self.manifold}")
        if self.split_file:
            parts.append(f"; the {self.split_points:,} split points are listed in "
                         f"{self.split_file} (a tool that merges duplicate vertices, as a "
                         "slicer reading STL does, joins them again)")
        return "".join(parts)


def is_closed(faces: np.ndarray) -> bool:
    """True when every directed edge of the (f, 3) triangles is matched by its reverse."""
    if len(faces) == 0:
        return False
    edges = faces[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2).astype(np.int64)
    n = int(faces.max()) + 1
    fwd = np.sort(edges[:, 0] * n + edges[:, 1])
    rev = np.sort(edges[:, 1] * n + edges[:, 0])
    return bool(np.array_equal(fwd, rev))


def _extension(path: Path, formats: dict[str, str]) -> str:
    """Lower-case extension of `path` if it is one of `formats`, else a clear error."""
    ext = path.suffix.lower()
    if ext not in formats:
        raise FileFormatError(f"{path}: cannot export to {ext or 'a file without extension'!r};"
                              f" choose one of {' '.join(formats)}")
    return ext


@contextlib.contextmanager
def _reported(path: Path) -> Iterator[None]:
    """Turn any failure while writing `path` into a FileFormatError naming the file.

    Our own errors (Cancelled, FileFormatError) pass through unchanged; so do KeyboardInterrupt
    and other BaseExceptions. The atomic write has already left any old file intact.
    """
    try:
        yield
    except AlphaScoopError:
        raise
    except OSError as exc:
        raise FileFormatError(f"{path}: cannot write ({exc.strerror or exc})") from None
    except Exception as exc:  # trimesh, shapely... raise ValueError and others
        problem = next(iter(str(exc).strip().splitlines()), "") or type(exc).__name__
        raise FileFormatError(f"{path}: cannot write ({problem})") from exc


def _write_surface(tmp: Path, ext: str, ac, shape, manifold: bool, meta: dict
                   ) -> tuple[dict, str | None]:
    """Write a triangle surface; returns the report fields and the CSV listing of the points
    a manifold split wrote more than once (None: none)."""
    vertices, faces, split = surface_arrays(ac, shape, manifold=manifold)
    meta.update(manifold_meta(split))
    SURFACE_WRITERS[ext](tmp, vertices, faces, meta)
    listing = split_listing(ac, split)
    return ({"n_vertices": len(vertices), "n_faces": len(faces),
             "closed": is_closed(faces) if ac.dim == 3 else None,
             "manifold": None if split is None else split.line(),
             "split_points": 0 if split is None else len(split.split_points)}, listing)


def _step(progress: Progress | None, fraction: float, stage: str) -> None:
    if progress is not None:
        progress(fraction, stage)


def write_shape(ac, alpha: float | None, path: str | os.PathLike, *, manifold: bool = True,
                sidecar: bool = False, source: str | os.PathLike | None = None,
                progress: Progress | None = None, georef: Georef | None = None,
                alpha2: float | None = None,
                point_data: dict[str, np.ndarray] | None = None) -> ExportReport:
    """Write ac.shape(alpha) (or, with alpha None, ac.shape(alpha2=alpha2): a squared value,
    negative ones for weighted points) in the format of `path`'s extension (SHAPE_FORMATS).

    3D: surfaces are the outward REGULAR facets, split where the shape touches itself so
    that they form a closed 2-manifold (`manifold=False`: the raw boundary, which slicers and
    CAD tools may reject); 2D: polygon formats, or the filled triangles for surface formats.
    `sidecar=True` also writes PATH.json with the metadata. A target (or sidecar) that is
    the `source` file itself is refused with an InputError before anything is written.
    `georef` (the load report's, for points read from longitude/latitude) puts GeoJSON, WKT
    and CSV back in WGS 84 longitude/latitude (WKT and CSV with a PATH.prj naming the CRS)
    and adds the projection and the ellipsoidal area and perimeter to the metadata.
    `point_data` ((m,) arrays aligned with ac.points, e.g. a molecule's `atom_area`) goes
    into formats that hold per-point values: .vtu. Points a manifold split wrote more than
    once are listed in PATH.split-points.csv (x, y, z, copies), so that the user knows what a
    merge of duplicate vertices undoes.
    """
    path = Path(path)
    ext = _extension(path, SHAPE_FORMATS)
    refuse_source(path, source)
    if sidecar:
        refuse_source(f"{path}.json", source)
    refuse_source(split_path(path), source)
    if georef is not None and ext in (".wkt", ".csv"):
        refuse_source(path.with_suffix(".prj"), source)
    if ac.dim == 3 and ext in POLYGON_WRITERS:
        raise FileFormatError(f"{path}: {ext} holds 2D polygons, but this shape is 3D; "
                              f"use one of {' '.join(SURFACE_WRITERS)} .vtu")
    _step(progress, 0.0, "computing the shape")
    shape = ac.shape(alpha) if alpha2 is None else ac.shape(alpha, alpha2=alpha2)
    meta = shape_metadata(ac, shape, source)
    if georef is not None:
        meta.update(geographic_metadata(ac, shape, georef))
    fields: dict = {}
    listing = None
    with _reported(path), atomic_path(path) as tmp:
        _step(progress, 0.2, f"writing {ext.lstrip('.').upper()}")
        if ext in POLYGON_WRITERS:
            POLYGON_WRITERS[ext](tmp, ac, shape, meta, georef)
        elif ext == ".vtu":
            write_vtu(tmp, ac, shape, meta, point_data)
        else:
            fields, listing = _write_surface(tmp, ext, ac, shape, manifold, meta)
        _step(progress, 0.95, "replacing the file")
    if listing is not None:
        with _reported(split_path(path)):
            atomic_write_text(split_path(path), listing)
        fields["split_file"] = str(split_path(path))
    if georef is not None and ext in (".wkt", ".csv"):
        with _reported(path.with_suffix(".prj")):
            fields["crs_file"] = str(write_prj(path))
    side = None
    if sidecar:
        side = str(path) + ".json"
        with _reported(Path(side)):
            atomic_write_text(side, sidecar_text(meta))
    return ExportReport(path=str(path), format=ext.lstrip(".").upper(), alpha=float(shape.alpha),
                        measure=float(shape.measure), sidecar=side, metadata=meta, **fields)


def split_path(path: Path) -> Path:
    """Where the points a manifold split wrote more than once are listed: PATH.split-points.csv."""
    return Path(f"{path}.split-points.csv")


def write_table(ac, path: str | os.PathLike, *, progress: Progress | None = None,
                source: str | os.PathLike | None = None) -> ExportReport:
    """Write the interval table as .npz (layout in core/export/table.py) or .csv, atomically.

    The report's n_faces counts the simplices of every dimension; its alpha is None. A target
    that is the `source` file (the points' file) is refused with an InputError.
    """
    path = Path(path)
    ext = _extension(path, TABLE_FORMATS)
    refuse_source(path, source)
    with _reported(path), atomic_path(path) as tmp:
        _step(progress, 0.0, f"writing {ext.lstrip('.').upper()}")
        TABLE_WRITERS[ext](tmp, ac)
        _step(progress, 0.95, "replacing the file")
    n = sum(len(ac.simplices(k)) for k in range(ac.dim + 1))
    return ExportReport(path=str(path), format=ext.lstrip(".").upper(), alpha=None,
                        n_vertices=len(ac.points), n_faces=n)

"""Mesh files contribute their vertices: OBJ/STL/OFF/GLB via trimesh, VTK formats via meshio."""

from __future__ import annotations

import logging
from pathlib import Path

import numpy as np

from core.errors import FileFormatError

TRIMESH_EXTS = {".obj", ".stl", ".off", ".glb", ".gltf"}
MESHIO_READERS = {".vtk": "vtk", ".vtu": "vtu"}  # meshio reads no VTP


def _trimesh_vertices(path: Path) -> tuple[np.ndarray, dict[str, np.ndarray]]:
    """All vertex records (no merging, so duplicates are counted by the report)."""
    import trimesh

    logging.getLogger("trimesh").setLevel(logging.ERROR)
    try:
        mesh = trimesh.load(str(path), process=False, force="mesh")
    except Exception as exc:  # trimesh raises anything from its many parsers
        raise FileFormatError(f"{path}: unreadable mesh ({type(exc).__name__}: {exc})") from None
    vertices = np.asarray(getattr(mesh, "vertices", np.empty((0, 3))), dtype=np.float64)
    attrs: dict[str, np.ndarray] = {}
    colors = getattr(getattr(mesh, "visual", None), "vertex_colors", None)
    if getattr(mesh.visual, "kind", None) == "vertex" and colors is not None:
        attrs["colors"] = np.asarray(colors)[:, :3].astype(np.uint8)
    return vertices, attrs


def _meshio_vertices(path: Path) -> tuple[np.ndarray, dict[str, np.ndarray]]:
    """Points of a VTK-family file plus its 1-component or 3-component point data."""
    import importlib

    module = importlib.import_module(f"meshio.{MESHIO_READERS[path.suffix.lower()]}")
    try:  # the format's own reader: meshio.read() calls sys.exit on failure
        mesh = module.read(str(path))
    except Exception as exc:  # meshio raises ReadError, ValueError, KeyError...
        raise FileFormatError(f"{path}: unreadable mesh ({type(exc).__name__}: {exc})") from None
    vertices = np.asarray(mesh.points, dtype=np.float64)
    attrs = {}
    for name, values in mesh.point_data.items():
        values = np.asarray(values)
        if len(values) == len(vertices) and np.issubdtype(values.dtype, np.number):
            attrs["normals" if name.lower() == "normals" else name] = values
    return vertices, attrs


def read_mesh(path: Path, columns=None) -> tuple[np.ndarray, dict[str, np.ndarray], tuple]:
    """(n, 3) vertex coordinates of a mesh file (its faces are ignored)."""
    ext = path.suffix.lower()
    reader = _trimesh_vertices if ext in TRIMESH_EXTS else _meshio_vertices
    vertices, attrs = reader(path)
    if vertices.ndim != 2 or vertices.shape[1] != 3 or len(vertices) == 0:
        raise FileFormatError(f"{path}: mesh has no vertices")
    return vertices, attrs, ("mesh vertices; faces ignored",)

"""Wavefront OBJ read directly: every `v` record is a point, whether or not a face uses it.

trimesh keeps only the vertices its faces reference (and makes a point-only OBJ a different
object), so the `v` lines are parsed here; `f` and `l` lines only tell which vertices are used.
"""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np

from core.errors import FileFormatError

_RECORD = re.compile(rb"^[ \t]*(v|f|l)[ \t]+([^\r\n#]*)", re.M)
_SLASHED = re.compile(rb"/\S*")
MAX_NUMBER_CHARS = 64  # longer 'numbers' are junk (and would size a bytes array for every row)


def _floats(rows: list[bytes], path: Path) -> np.ndarray:
    """(n, k) float64 of `v` rows cut to their shortest common length (3, 4, 6 or 7 numbers)."""
    fields = [r.split() for r in rows]
    width = min(map(len, fields))
    if width < 3:
        raise FileFormatError(f"{path}: OBJ vertex with fewer than 3 coordinates")
    if max(len(t) for f in fields for t in f[:width]) > MAX_NUMBER_CHARS:  # bytes_ pads to it
        raise FileFormatError(f"{path}: OBJ vertex with a value that is not a number")
    try:
        return np.array([f[:width] for f in fields], dtype=np.bytes_).astype(np.float64)
    except ValueError:
        raise FileFormatError(f"{path}: OBJ vertex with a value that is not a number") from None


def _used(records: list[tuple[bytes, bytes]], n: int, path: Path) -> np.ndarray:
    """(n,) bool: vertices some face or line references (negative indices are relative)."""
    is_vertex = np.fromiter((kind == b"v" for kind, _ in records), dtype=bool, count=len(records))
    before = np.cumsum(is_vertex)[~is_vertex]  # vertices defined before each face or line
    bodies = [body for kind, body in records if kind != b"v"]
    seen = np.zeros(n, dtype=bool)
    if not bodies:
        return seen
    lengths = np.fromiter(map(len, map(bytes.split, bodies)), dtype=np.int64, count=len(bodies))
    refs = _SLASHED.sub(b"", b" ".join(bodies)).split()  # 'i/t/n' -> 'i'
    if refs and max(map(len, refs)) > MAX_NUMBER_CHARS:
        raise FileFormatError(f"{path}: OBJ face with an index that is not a number")
    try:
        idx = np.array(refs, dtype=np.bytes_).astype(np.int64)
    except ValueError:
        raise FileFormatError(f"{path}: OBJ face with an index that is not a number") from None
    idx = np.where(idx < 0, np.repeat(before, lengths) + idx, idx - 1)
    if idx.size and (idx.min() < 0 or idx.max() >= n):
        raise FileFormatError(f"{path}: OBJ face refers to a vertex that does not exist")
    seen[idx] = True
    return seen


def read_obj(path: Path, columns=None) -> tuple[np.ndarray, dict[str, np.ndarray], tuple]:
    """(n, 3) points of every `v` line, colours when `v x y z r g b`, and a note on unused ones."""
    records = _RECORD.findall(path.read_bytes())
    rows = [body for kind, body in records if kind == b"v"]
    if not rows:
        raise FileFormatError(f"{path}: OBJ file has no vertex ('v') lines")
    table = _floats(rows, path)
    attrs: dict[str, np.ndarray] = {}
    if table.shape[1] in (6, 7):
        scale = 255.0 if np.nanmax(table[:, 3:6], initial=0.0) <= 1.0 else 1.0
        attrs["colors"] = np.clip(np.nan_to_num(table[:, 3:6] * scale), 0, 255).astype(np.uint8)
    used = _used(records, len(rows), path)
    n_faces = len(records) - len(rows)
    return table[:, :3], attrs, (vertex_note(len(rows), int(used.sum()), n_faces),)


def vertex_note(n_vertices: int, n_used: int, n_elements: int) -> str:
    """Report line: how many vertex records no face uses (they are all kept as points)."""
    if n_elements == 0:
        return f"mesh vertices: {n_vertices:,} points, no faces"
    return (f"mesh vertices: all {n_vertices:,} kept; {n_vertices - n_used:,} used by no face "
            f"({n_elements:,} faces/lines ignored)")

"""The alpha complex at one alpha as a VTU for ParaView: cells and boundary simplices with data.

Blocks: the cells in the complex (INTERIOR), the REGULAR facets, and the SINGULAR simplices of
every lower dimension. Cell data: `class` (0-3), `dimension`, and the simplex's `enter`,
`regular` and `interior` alphas (radii; inf = never). Metadata goes into field data.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from core.export.vtkxml import vtu_bytes

INTERIOR, REGULAR, SINGULAR = 3, 2, 1


def complex_blocks(ac, shape) -> tuple[list[np.ndarray], dict[str, np.ndarray]]:
    """Cell blocks (highest dimension first) and their concatenated cell data."""
    dim = ac.dim
    parts = [(dim, np.asarray(shape.cell_ids), INTERIOR)]
    parts.append((dim - 1, np.asarray(shape.regular_facet_ids), REGULAR))
    for k in range(dim - 1, -1, -1):
        parts.append((k, np.asarray(shape.singular_ids(k)), SINGULAR))
    blocks, data = [], {"class": [], "dimension": [], "enter": [], "regular": [], "interior": []}
    for k, rows, cls in parts:
        if len(rows) == 0:
            continue
        blocks.append(np.asarray(ac.simplices(k))[rows])
        iv = np.asarray(ac.intervals(k))[rows]
        data["class"].append(np.full(len(rows), cls, dtype=np.int8))
        data["dimension"].append(np.full(len(rows), k, dtype=np.int8))
        for j, name in enumerate(("enter", "regular", "interior")):
            data[name].append(iv[:, j])
    return blocks, {k: np.concatenate(v) for k, v in data.items() if v}


def write_vtu(path: Path, ac, shape, meta: dict, point_data: dict | None = None) -> None:
    """Write the complex at shape.alpha as VTU (points in the input's space), with optional
    point data ((m,) arrays aligned with ac.points, by name)."""
    blocks, data = complex_blocks(ac, shape)
    points = np.asarray(ac.to_ambient(ac.points), dtype=np.float64)
    if points.shape[1] == 2:
        points = np.column_stack([points, np.zeros(len(points))])
    if not blocks:
        blocks = [np.empty((0, 1), dtype=np.int64)]
    path.write_bytes(vtu_bytes(points, blocks, data, meta, point_data))

"""Points into tiles: each tile gets its core points and every point within its margin.

In memory (`tile_groups`) for arrays, and streamed (`write_parts`) for inputs larger than
memory: each chunk of points is split and appended to per-tile .npy files under a scratch
folder, so no step holds more than one chunk (plus one tile, in the tile's task). A source
read by box (COPC) writes each tile's points at once (`write_tile`).
"""

from __future__ import annotations

import os
from collections.abc import Iterator
from pathlib import Path

import numpy as np

from core.storage.atomic import atomic_path
from core.tiled.plan import TilePlan

#: Columns of a part file: input row, 1.0 if in the tile's core, coordinates, [weight].
ROW, CORE, FIRST_COORD = 0, 1, 2


def tile_rows(plan: TilePlan, coords: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(rows, tiles, in_core): each point paired with every tile it belongs to (core or
    margin), grouped by tile (stable: rows ascending within a tile), and whether the point
    is in that tile's core."""
    rows, tiles = plan.touching(coords)
    order = np.lexsort((rows, tiles))
    rows, tiles = rows[order], tiles[order]
    return rows, tiles, plan.core_tile(coords[rows]) == tiles


def tile_groups(plan: TilePlan, coords: np.ndarray) -> Iterator[tuple[int, np.ndarray,
                                                                      np.ndarray]]:
    """(tile, rows, in_core) for every tile that has points in its core."""
    rows, tiles, in_core = tile_rows(plan, coords)
    starts = np.flatnonzero(np.r_[True, tiles[1:] != tiles[:-1]])
    for lo, hi in zip(starts, np.r_[starts[1:], len(tiles)], strict=True):
        if in_core[lo:hi].any():
            yield int(tiles[lo]), rows[lo:hi], in_core[lo:hi]


def tile_folder(scratch: Path, tile: int) -> Path:
    """The folder of one tile's part files."""
    return scratch / "tiles" / f"t{tile:07d}"


def write_parts(plan: TilePlan, scratch: Path, chunk: int, first_row: int,
                coords: np.ndarray, weights: np.ndarray | None) -> set[int]:
    """Append one chunk of points (input rows from `first_row`) to the part files of the
    tiles it touches (one file per tile and chunk, written atomically); the tiles with a
    core point in this chunk."""
    rows, tiles, in_core = tile_rows(plan, coords)
    columns = [(rows + first_row).astype(np.float64), in_core.astype(np.float64),
               *coords[rows].T]
    if weights is not None:
        columns.append(weights[rows])
    table = np.column_stack(columns)
    starts = np.flatnonzero(np.r_[True, tiles[1:] != tiles[:-1]])
    for lo, hi in zip(starts, np.r_[starts[1:], len(tiles)], strict=True):
        _save_part(scratch, int(tiles[lo]), chunk, table[lo:hi])
    return {int(t) for t in np.unique(tiles[in_core])}


def write_tile(scratch: Path, tile: int, rows: np.ndarray, in_core: np.ndarray,
               coords: np.ndarray, weights: np.ndarray | None) -> None:
    """One tile's points at once (input `rows` ascending), as the one part file
    `write_parts` would have split them into (a source read by box: core.tiled.copc)."""
    columns = [rows.astype(np.float64), in_core.astype(np.float64), *coords.T]
    if weights is not None:
        columns.append(weights)
    _save_part(scratch, tile, 0, np.column_stack(columns))


def _save_part(scratch: Path, tile: int, chunk: int, table: np.ndarray) -> None:
    """Write one part file of a tile atomically."""
    folder = tile_folder(scratch, tile)
    os.makedirs(folder, exist_ok=True)
    with atomic_path(folder / f"c{chunk:06d}.npy") as tmp, open(tmp, "wb") as fh:
        np.save(fh, table, allow_pickle=False)


def read_tile(folder: Path, dim: int, weighted: bool
              ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray | None]:
    """(rows, coords, in_core, weights) of one tile from its part files."""
    parts = [np.load(p, allow_pickle=False) for p in sorted(Path(folder).glob("c*.npy"))]
    table = np.concatenate(parts) if parts else np.empty((0, FIRST_COORD + dim + weighted))
    rows = table[:, ROW].astype(np.int64)
    coords = np.ascontiguousarray(table[:, FIRST_COORD:FIRST_COORD + dim])
    weights = table[:, FIRST_COORD + dim] if weighted else None
    return rows, coords, table[:, CORE] > 0, weights

"""The octree index of a COPC file (LAZ 1.4 whose points are grouped in an octree, indexed
in hierarchy pages): the nodes that hold points, with their boxes, byte ranges and file
rows, read from the pages and checked against the file.

Every node is one LAZ chunk and the chunks follow one another in the file in offset order,
so a point's row in the file (the row laspy's readers give it) is the count of points in
the nodes before its node plus its place in the node. laspy's CopcReader.query gives a
box's points without those rows, which a tile needs (core.tiled.copc).
"""

from __future__ import annotations

import os
from dataclasses import dataclass

import numpy as np

from core.errors import FileFormatError

#: One hierarchy entry (COPC 1.0): voxel key (level, x, y, z), offset and bytes of its
#: LAZ chunk (or of a child page when count is -1), points in the chunk.
ENTRY = np.dtype([("key", "<i4", 4), ("offset", "<u8"), ("size", "<i4"), ("count", "<i4")])
#: Deepest octree level taken as plausible (a node side of 2^-40 of the root's).
MAX_LEVEL = 40


def is_copc(path: str | os.PathLike) -> bool:
    """Whether a LAS/LAZ file carries the COPC info VLR (laspy parses it)."""
    import laspy
    from laspy.copc import CopcInfoVlr

    with laspy.open(str(path)) as reader:
        return any(isinstance(vlr, CopcInfoVlr) for vlr in reader.header.vlrs)


@dataclass(frozen=True)
class Octree:
    """The nodes that hold points, in file order: `lo`, `hi` (k, 3) float64 boxes, `offset`,
    `size` (k,) int64 byte range of each LAZ chunk, `count` (k,) points, `first` (k,) row
    of each node's first point in the file, `level` (k,) its depth in the octree."""

    lo: np.ndarray
    hi: np.ndarray
    offset: np.ndarray
    size: np.ndarray
    count: np.ndarray
    first: np.ndarray
    level: np.ndarray


def read_octree(fh, header, file_size: int) -> tuple[Octree, bytes]:
    """(octree, LASzip VLR data) of an open COPC file whose laspy `header` was read;
    FileFormatError without the path for a damaged index."""
    from laspy.copc import CopcInfoVlr
    from laspy.vlrs.known import LasZipVlr

    info = _vlr(header, CopcInfoVlr)
    laszip = bytes(_vlr(header, LasZipVlr).record_data)
    return _octree(fh, header, info, file_size), laszip


def _vlr(header, kind):
    """The header's VLR of this laspy class; FileFormatError when it has none."""
    found = [vlr for vlr in header.vlrs if isinstance(vlr, kind)]
    if not found:
        raise FileFormatError(f"damaged COPC file (no {kind.__name__})")
    return found[0]


def _octree(fh, header, info, file_size: int) -> Octree:
    """Every node holding points, from the hierarchy pages, checked against the file
    (FileFormatError without the path: pages or chunks outside the file or overlapping,
    keys outside the octree, counts that do not add up to the header's)."""
    entries = _entries(fh, int(info.hierarchy_root_offset), int(info.hierarchy_root_size),
                       file_size)
    key, count = entries["key"], entries["count"].astype(np.int64)
    level = key[:, 0].astype(np.int64)
    if (count < 0).any() or (level < 0).any() or (level > MAX_LEVEL).any():
        raise FileFormatError("damaged COPC hierarchy (a count or level out of range)")
    cells = key[:, 1:].astype(np.int64)
    if ((cells < 0) | (cells >= (np.int64(1) << level)[:, None])).any():
        raise FileFormatError("damaged COPC hierarchy (a node outside the octree)")
    held = np.flatnonzero(count > 0)
    if (entries["offset"][held] > file_size).any():
        raise FileFormatError("damaged COPC hierarchy (chunks outside the file or overlapping)")
    order = held[np.argsort(entries["offset"][held], kind="stable")]
    offset = entries["offset"][order].astype(np.int64)
    size = entries["size"][order].astype(np.int64)
    count = count[order]
    start = int(header.offset_to_point_data) + 8  # after the LAZ chunk table's offset
    inside = (size > 0).all() and (len(offset) == 0 or (offset[0] >= start
                                                        and offset[-1] + size[-1] <= file_size))
    if not inside or (offset[1:] < offset[:-1] + size[:-1]).any():
        raise FileFormatError("damaged COPC hierarchy (chunks outside the file or overlapping)")
    if int(count.sum()) != int(header.point_count):
        raise FileFormatError(f"damaged COPC hierarchy ({int(count.sum()):,} points in its "
                              f"nodes, {int(header.point_count):,} in the header)")
    halfsize, centre = float(info.halfsize), np.asarray(info.center, dtype=np.float64)
    if not (np.isfinite(halfsize) and halfsize > 0 and np.isfinite(centre).all()):
        raise FileFormatError("damaged COPC info (octree box not finite)")
    side = 2.0 * halfsize / np.ldexp(1.0, level[order])[:, None]
    lo = centre - halfsize + cells[order] * side
    first = np.cumsum(count) - count
    return Octree(lo, lo + side, offset, size, count, first, level[order])


def _entries(fh, root: int, root_size: int, file_size: int) -> np.ndarray:
    """Every entry of the hierarchy's pages (child-page entries followed, not returned)."""
    pages, seen, out, total = [(root, root_size)], set(), [], 0
    while pages:
        offset, size = pages.pop()
        total += size
        if ((offset, size) in seen or size < 0 or size % ENTRY.itemsize
                or offset + size > file_size or total > file_size):
            raise FileFormatError("damaged COPC hierarchy (a page outside the file)")
        seen.add((offset, size))
        fh.seek(offset)
        raw = fh.read(size)
        if len(raw) != size:
            raise FileFormatError("damaged COPC hierarchy (a page past the end of the file)")
        page = np.frombuffer(raw, dtype=ENTRY)
        child = page["count"] == -1
        pages.extend(zip(page["offset"][child].tolist(), page["size"][child].tolist(),
                         strict=True))
        out.append(page[~child])
    return np.concatenate(out)

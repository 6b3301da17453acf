"""COPC files (LAZ 1.4 whose points are grouped in an octree, indexed in a VLR) read by their
index: the points of a box, each with its row in the file, decoding only the octree nodes
whose box meets it.

laspy's CopcReader.query returns a box's points without their rows, and a tile needs them
(simplices are kept and numbered by input row: core.tiled). So the nodes are listed here
from the hierarchy pages and decoded with lazrs, as CopcReader does: every node is one LAZ
chunk and the chunks follow one another in the file in offset order, so a point's row is
the count of points in the nodes before its node in the file plus its place in the node,
the row laspy's chunked reader gives it.
"""

from __future__ import annotations

import os
from collections import OrderedDict
from collections.abc import Iterator
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from core.errors import FileFormatError
from core.tiled.sources import CHUNK_POINTS

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


@dataclass(frozen=True)
class CopcSource:
    """A COPC file: streamed node by node in file order (`chunks`, as core.tiled.sources),
    or read by box through its octree (`box`). Open it with `CopcSource.open`. `chunk`
    bounds the points of a streamed chunk and of the nodes `box` keeps decoded between
    calls (`kept`: the coarse nodes that neighbouring tiles read again)."""

    path: Path
    octree: Octree
    laszip: bytes
    point_format: object
    scales: np.ndarray
    offsets: np.ndarray
    chunk: int = CHUNK_POINTS
    weights: None = None
    frame: None = None
    ambient_dim: int = 3
    dim: int = 3
    kept: OrderedDict = field(default_factory=OrderedDict, compare=False, repr=False)

    @classmethod
    def open(cls, path: str | os.PathLike, chunk: int = CHUNK_POINTS) -> CopcSource:
        """The file's header and octree; FileFormatError (one line) for a damaged index."""
        import laspy
        from laspy.copc import CopcInfoVlr
        from laspy.vlrs.known import LasZipVlr

        path = Path(path)
        try:
            with laspy.open(str(path)) as reader:
                header = reader.header
            info = _vlr(header, CopcInfoVlr)
            laszip = bytes(_vlr(header, LasZipVlr).record_data)
            with open(path, "rb") as fh:
                octree = _octree(fh, header, info, os.path.getsize(path))
        except FileFormatError as exc:
            raise FileFormatError(f"{path}: {exc}") from None
        except Exception as exc:  # laspy or the OS on a damaged header or VLR
            raise _damaged(path, exc) from exc
        scales, offsets = np.asarray(header.scales), np.asarray(header.offsets)
        if not (np.isfinite(scales).all() and np.isfinite(offsets).all() and scales.all()):
            raise FileFormatError(f"{path}: damaged COPC header (scale or offset not finite)")
        return cls(path, octree, laszip, header.point_format, scales, offsets, chunk)

    @property
    def count(self) -> int:
        """Points in the file."""
        return int(self.octree.count.sum())

    def chunks(self) -> Iterator[tuple[np.ndarray, None]]:
        """(coords, None) chunks of whole nodes in file order (rows as laspy's chunked
        reader numbers them); FileFormatError if a point lies outside its node's box (the
        box queries rely on it)."""
        tree = self.octree
        ends = np.cumsum(tree.count)
        start = 0
        while start < len(tree.count):
            stop = max(start + 1, int(np.searchsorted(ends, ends[start] - tree.count[start]
                                                     + self.chunk, side="right")))
            nodes = np.arange(start, stop)
            coords = self._decode(nodes)
            self._check_inside(nodes, coords)
            yield coords, None
            start = stop

    def box(self, lo: np.ndarray, hi: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(rows (n,) int64 ascending, coords (n, 3)) of every point of the nodes whose box
        meets [lo, hi] (inf allowed): a superset of the box's points, from those nodes
        only."""
        tree, slack = self.octree, self._slack
        meets = np.all((tree.lo - slack <= np.asarray(hi)) & (np.asarray(lo) <= tree.hi + slack),
                       axis=1)
        nodes = np.flatnonzero(meets)
        coords = self._recalled(nodes)
        rows = np.repeat(tree.first[nodes] - np.cumsum(tree.count[nodes]) + tree.count[nodes],
                         tree.count[nodes]) + np.arange(len(coords))
        return rows, coords

    def _recalled(self, nodes: np.ndarray) -> np.ndarray:
        """(n, 3) coordinates of `nodes` (file order): the kept ones as kept, the others
        decoded; then the coarsest are kept first, least recently used out beyond `chunk`
        points."""
        tree, kept = self.octree, self.kept
        missing = np.asarray([n for n in nodes.tolist() if n not in kept], dtype=np.int64)
        fresh = self._decode(missing)
        parts = {} if len(missing) == 0 else dict(zip(
            missing.tolist(), np.split(fresh, np.cumsum(tree.count[missing])[:-1]), strict=True))
        out = [kept[n] if n in kept else parts[n] for n in nodes.tolist()]
        for n in nodes[np.argsort(-tree.level[nodes], kind="stable")].tolist():
            kept[n] = kept.pop(n) if n in kept else parts[n]
        held = sum(len(c) for c in kept.values())
        while held > self.chunk:
            held -= len(kept.popitem(last=False)[1])
        return np.concatenate(out) if out else np.empty((0, 3))

    @property
    def _slack(self) -> float:
        """How far outside its node's box a point may lie: one unit of the coordinates'
        quantization (a writer puts a point in a node from its scaled value)."""
        return float(np.abs(self.scales).max())

    def _check_inside(self, nodes: np.ndarray, coords: np.ndarray) -> None:
        """FileFormatError unless each point lies in its node's box (within the slack)."""
        tree = self.octree
        owner = np.repeat(nodes, tree.count[nodes])
        slack = self._slack
        outside = ~np.all((tree.lo[owner] - slack <= coords) & (coords <= tree.hi[owner] + slack),
                          axis=1)
        if outside.any():
            raise FileFormatError(f"{self.path}: damaged COPC index ({int(outside.sum()):,} "
                                  f"points outside their octree node)")

    def _decode(self, nodes: np.ndarray) -> np.ndarray:
        """(n, 3) float64 coordinates of the points of `nodes` (file order), decoded with
        lazrs (coordinates only); FileFormatError for damaged chunks."""
        import laspy
        import lazrs

        tree = self.octree
        if len(nodes) == 0:
            return np.empty((0, 3))
        counts, sizes = tree.count[nodes], tree.size[nodes]
        data = bytearray(int(sizes.sum()))
        view = memoryview(data)
        try:
            with open(self.path, "rb") as fh:
                at = 0
                for offset, size in zip(tree.offset[nodes], sizes, strict=True):
                    fh.seek(int(offset))
                    if fh.readinto(view[at:at + int(size)]) != size:
                        raise FileFormatError("a chunk runs past the end of the file")
                    at += int(size)
            out = np.zeros(int(counts.sum()) * self.point_format.size, dtype=np.uint8)
            selection = (laspy.DecompressionSelection.XY_RETURNS_CHANNEL
                         | laspy.DecompressionSelection.Z)
            lazrs.decompress_points_with_chunk_table(
                data, self.laszip, out, [(int(c), int(s)) for c, s in zip(counts, sizes,
                                                                        strict=True)],
                selection.to_lazrs())
        except BaseException as exc:  # lazrs reports corrupt data as a Rust panic
            if not isinstance(exc, Exception) and type(exc).__name__ != "PanicException":
                raise
            raise _damaged(self.path, exc) from None
        record = laspy.PackedPointRecord.from_buffer(out, self.point_format)
        points = laspy.ScaleAwarePointRecord(record.array, record.point_format, self.scales,
                                             self.offsets)
        return np.column_stack([np.asarray(points.x, dtype=np.float64),
                                np.asarray(points.y, dtype=np.float64),
                                np.asarray(points.z, dtype=np.float64)])


def _damaged(path: Path, exc: BaseException) -> FileFormatError:
    """The one-line error of a COPC file laspy or lazrs could not read."""
    reason = str(exc).splitlines()[0] if str(exc) else type(exc).__name__
    return FileFormatError(f"{path}: damaged COPC file ({reason})")


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

"""COPC files read by their index: the points of a box, each with its row in the file,
decoding only the octree nodes whose box meets it (core.tiled.octree lists them), with
lazrs as laspy's CopcReader does; and the whole file streamed node by node in file order,
checking that every point lies in its node's box (else the run streams as for a plain
LAZ: the index is only a shortcut).
"""

from __future__ import annotations

import os
from collections import OrderedDict
from collections.abc import Iterator
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from core.errors import FileFormatError
from core.tiled.octree import Octree, read_octree
from core.tiled.sources import CHUNK_POINTS


@dataclass(frozen=True)
class CopcSource:
    """A COPC file: streamed node by node in file order (`chunks`, as core.tiled.sources),
    or read by box through its octree (`box`). Open it with `CopcSource.open`. `chunk`
    bounds the points of a streamed chunk and of the nodes `box` keeps decoded between
    calls (`kept`: the coarse nodes that neighbouring tiles read again); `checked` holds
    what the last whole pass found (`index_holds`)."""

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
    checked: dict = field(default_factory=dict, compare=False, repr=False)

    @classmethod
    def open(cls, path: str | os.PathLike, chunk: int = CHUNK_POINTS) -> CopcSource:
        """The file's header and octree; FileFormatError (one line) for a damaged index."""
        import laspy

        path = Path(path)
        try:
            with laspy.open(str(path)) as reader:
                header = reader.header
            with open(path, "rb") as fh:
                octree, laszip = read_octree(fh, header, os.path.getsize(path))
        except FileFormatError as exc:
            raise FileFormatError(f"{path}: {exc}") from None
        except Exception as exc:  # laspy or the OS on a damaged header or VLR
            raise _damaged(path, exc) from exc
        scales, offsets = np.asarray(header.scales), np.asarray(header.offsets)
        if not (np.isfinite(scales).all() and np.isfinite(offsets).all() and scales.all()):
            raise FileFormatError(f"{path}: damaged COPC header (scale or offset not finite)")
        return cls(path, octree, laszip, header.point_format, scales, offsets, chunk)

    @property
    def index_holds(self) -> bool:
        """Whether a whole pass of `chunks` found every point in its node's box (what `box`
        relies on)."""
        return self.checked.get("outside") == 0

    def chunks(self) -> Iterator[tuple[np.ndarray, None]]:
        """(coords, None) chunks of whole nodes in file order (rows as laspy's chunked
        reader numbers them); counts the points outside their node's box (`index_holds`)."""
        tree = self.octree
        ends = np.cumsum(tree.count)
        start, outside = 0, 0
        while start < len(tree.count):
            stop = max(start + 1, int(np.searchsorted(ends, ends[start] - tree.count[start]
                                                     + self.chunk, side="right")))
            nodes = np.arange(start, stop)
            coords = self._decode(nodes)
            outside += self._outside(nodes, coords)
            yield coords, None
            start = stop
        self.checked["outside"] = outside

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

    def _outside(self, nodes: np.ndarray, coords: np.ndarray) -> int:
        """How many points of `nodes` lie outside their node's box (beyond the slack)."""
        tree = self.octree
        owner = np.repeat(nodes, tree.count[nodes])
        slack = self._slack
        inside = np.all((tree.lo[owner] - slack <= coords) & (coords <= tree.hi[owner] + slack),
                        axis=1)
        return int(np.count_nonzero(~inside))

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

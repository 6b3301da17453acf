"""The result of reading a point file: clean points, their attributes, and a load report."""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
from scipy.spatial import cKDTree

from core.arrays import contiguous_readonly
from core.build.points import clearly_spread, first_too_large, flatness, too_large_message
from core.errors import FileFormatError
from core.geometry.georef import Georef
from core.io.subsample import first_unique, subsample_indices
from core.io.view_hint import ViewHint
from core.parallel import both
from core.tolerances import FLAT_RTOL

SPACING_SAMPLE = 100_000  # query points used to estimate the median nearest-neighbour distance


@dataclass(frozen=True)
class Skipped:
    """Records a reader left out, with the reason in words ('have no range (direction
    only)'): they count in the records read, beside non-finite and duplicate points."""

    count: int
    reason: str

    def __str__(self) -> str:
        return f"{self.count:,} {self.reason}"


@dataclass(frozen=True)
class LoadReport:
    """What a reader found and changed; shown by the app's Data panel and `alphascoop info`."""

    path: str
    format: str
    n_read: int
    n_points: int
    n_nonfinite: int
    n_duplicates: int
    dim: int
    planar: bool
    bbox: tuple[tuple[float, ...], tuple[float, ...]]
    spacing: float
    attributes: tuple[str, ...]
    subsampled_from: int | None = None
    subsample_method: str | None = None
    notes: tuple[str, ...] = ()
    georef: Georef | None = None
    weights_from: str | None = None  # where the weights (squared radii) came from; None: none
    #: records the reader left out before these counts (in n_read too), with their reasons
    skipped: tuple[Skipped, ...] = ()
    #: which way is up (and forward) where the file says it (core.io.view_hint), else None
    view: ViewHint | None = None

    def to_dict(self) -> dict:
        """Plain JSON-ready dict (lists instead of tuples)."""
        out = dataclasses.asdict(self)
        out["bbox"] = [list(c) for c in self.bbox]
        out["attributes"] = list(self.attributes)
        out["notes"] = list(self.notes)
        out["georef"] = None if self.georef is None else self.georef.to_dict()
        out["skipped"] = [{"count": k.count, "reason": k.reason} for k in self.skipped]
        return out

    def count_line(self) -> str:
        """'977 of 978 points read (1 non-finite dropped)' or '180 of 360 records read (180
        have no range (direction only))': the points kept, the records read, and why the others
        were dropped (the window and `alphascoop info` both say this)."""
        kind = "records" if self.skipped else "points"
        reasons = [str(k) for k in self.skipped]
        if self.n_nonfinite:
            reasons.append(f"{self.n_nonfinite:,} non-finite dropped")
        if self.n_duplicates:
            reasons.append(f"{self.n_duplicates:,} duplicates merged")
        return (f"{self.n_points:,} of {self.n_read:,} {kind} read"
                + (f" ({'; '.join(reasons)})" if reasons else ""))

    def lines(self) -> list[str]:
        """Short human-readable summary, one fact per line."""
        lo, hi = self.bbox
        out = [
            f"file        {self.path} ({self.format})",
            f"points      {self.count_line()}",
            f"dimension   {self.dim}D{' (planar)' if self.planar and self.dim == 3 else ''}",
            f"bbox        [{', '.join(f'{v:.6g}' for v in lo)}] - "
            f"[{', '.join(f'{v:.6g}' for v in hi)}]",
            f"spacing     {self.spacing:.6g} (median nearest-neighbour distance)",
            f"attributes  {', '.join(self.attributes) or 'none'}",
        ]
        if self.weights_from is not None:
            out.append(f"weights     {self.weights_from}")
        if self.subsampled_from is not None:
            out.append(f"subsampled  {self.subsample_method} from {self.subsampled_from:,}")
        if self.georef is not None:
            out.append(f"projection  {self.georef.line()}")
        out.extend(f"note        {n}" for n in self.notes)
        return out


@dataclass(frozen=True)
class PointSet:
    """Points (n, d) float64 (d = 2 or 3), per-point attributes (n, ...), and the load report."""

    points: np.ndarray
    attributes: dict[str, np.ndarray] = field(default_factory=dict)
    report: LoadReport | None = None

    @property
    def weights(self) -> np.ndarray | None:
        """(n,) float64 squared radii of a weighted point set, else None."""
        if self.report is None or self.report.weights_from is None:
            return None
        return self.attributes.get("weights")


def is_planar(points: np.ndarray) -> bool:
    """True for 2D points, or 3D points whose spread across some plane is negligible."""
    if points.shape[1] == 2 or len(points) < 4:
        return True
    if clearly_spread(points):  # most scans: no SVD needed
        return False
    s = flatness(points)[1]
    return bool(s[-1] <= FLAT_RTOL * s[0])


def median_spacing(points: np.ndarray, seed: int = 0) -> float:
    """Median distance from a point to its nearest neighbour (on a sample for big sets).

    The tree is built unbalanced and without shrunk nodes, which is quicker to build: the
    distances a query finds are the same in any tree (the nearest neighbours' exact ones).
    """
    if len(points) < 2:
        return 0.0
    tree = cKDTree(points, balanced_tree=False, compact_nodes=False)
    query = points
    if len(points) > SPACING_SAMPLE:
        rng = np.random.default_rng(seed)
        query = points[rng.choice(len(points), SPACING_SAMPLE, replace=False)]
    dist, _ = tree.query(query, k=2)
    return float(np.median(dist[:, 1]))


def nonfinite_attributes(attributes: dict[str, np.ndarray]) -> tuple[str, ...]:
    """Warnings for float attributes holding NaN or infinite values (kept as they are)."""
    out = []
    for name, values in sorted(attributes.items()):
        if np.issubdtype(values.dtype, np.floating) and values.size:
            bad = int(np.count_nonzero(~np.isfinite(values).reshape(len(values), -1).all(axis=1)))
            if bad:
                out.append(f"warning: attribute {name!r} has {bad:,} non-finite values")
    return tuple(out)


def _heaviest_unique(points: np.ndarray, weights: np.ndarray | None) -> np.ndarray:
    """(n,) bool mask keeping one of each group of duplicate rows: the first, or for weighted
    points the first of the heaviest (a lighter ball at the same place is hidden anyway)."""
    if weights is None:
        return first_unique(points)
    order = np.argsort(-np.nan_to_num(weights, nan=-np.inf), kind="stable")
    keep = np.empty(len(points), dtype=bool)
    keep[order] = first_unique(points[order])
    return keep


def finish(
    path: Path,
    fmt: str,
    points: np.ndarray,
    attributes: dict[str, np.ndarray],
    *,
    subsample: int | None = None,
    method: str = "voxel",
    seed: int = 0,
    notes: tuple[str, ...] = (),
    georef: Georef | None = None,
    weights_from: str | None = None,
    skipped: tuple[Skipped, ...] = (),
    view: ViewHint | None = None,
) -> PointSet:
    """Drop non-finite rows, merge duplicates, subsample, and measure: the common reader tail
    (`skipped`: records the reader left out, counted in the records read)."""
    points = np.asarray(points, dtype=np.float64)
    n_read = len(points) + sum(k.count for k in skipped)
    if points.ndim == 2 and points.shape[1] in (2, 3):
        extreme = first_too_large(points)
        if extreme is not None:
            raise FileFormatError(f"{path}: {too_large_message(points, *extreme)}")
    finite = np.all(np.isfinite(points), axis=1)
    points = points[finite]
    attributes = {k: np.asarray(v)[finite] for k, v in attributes.items()}
    notes = tuple(notes) + nonfinite_attributes(attributes)
    keep = _heaviest_unique(points, attributes.get("weights") if weights_from else None)
    n_dup = int(len(points) - keep.sum())
    points = points[keep]
    attributes = {k: v[keep] for k, v in attributes.items()}
    before = len(points)
    if subsample is not None and 0 < subsample < before:
        idx = subsample_indices(points, subsample, method=method, seed=seed)
        points = points[idx]
        attributes = {k: v[idx] for k, v in attributes.items()}
    lo = points.min(axis=0) if len(points) else np.zeros(points.shape[1])
    hi = points.max(axis=0) if len(points) else np.zeros(points.shape[1])
    # the two measures release the GIL: the planarity's SVD beside the spacing's tree
    planar, spacing = both(lambda: is_planar(points), lambda: median_spacing(points, seed))
    report = LoadReport(
        path=str(path),
        format=fmt,
        n_read=n_read,
        n_points=len(points),
        n_nonfinite=int(len(finite) - finite.sum()),
        n_duplicates=n_dup,
        dim=points.shape[1],
        planar=planar,
        bbox=(tuple(map(float, lo)), tuple(map(float, hi))),
        spacing=spacing,
        attributes=tuple(sorted(attributes)),
        subsampled_from=before if len(points) < before else None,
        subsample_method=method if len(points) < before else None,
        notes=notes,
        georef=georef,
        weights_from=weights_from,
        skipped=tuple(skipped),
        view=view,
    )
    return PointSet(
        points=contiguous_readonly(points),
        attributes={k: contiguous_readonly(v) for k, v in attributes.items()},
        report=report,
    )

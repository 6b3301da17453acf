"""A triangulation in two halves at once, joined exactly: Qhull's (Qhull releases the GIL: two
threads) or gmsh's (gmsh holds global state: the second half in a child process,
core.backends.gmsh_half).

The points are split at the median of their longest axis and both halves are triangulated
at the same time (Delaunay; regular for weighted points, Qhull only). A half's cell whose
circumsphere (orthosphere) a float test with a margin (SPLIT_EMPTY_RTOL) finds empty of the
other half's points is kept as a cell of the whole triangulation. The band the kept cells
leave around the split (and, for gmsh, the cells it drops near each half's hull) is restored
as core.backends.restore restores gmsh's dropped cells: the triangulation of the kept union's
boundary vertices and of the points in no kept cell, flooded from that boundary. The joined
result is then checked (core.backends.certify): a triangulation of the hull, and every facet
of a cell near the join locally Delaunay (regular) by a margin. A cell kept by mistake cannot
pass: by the Delaunay lemma a triangulation that is not Delaunay has a locally non-Delaunay
facet, and the facets inside one half are Qhull's own (trusted as one Qhull call is) or
gmsh's (each checked in its half), so that facet lies at the join, where it is checked. On
any doubt the caller triangulates in one call.
"""

from __future__ import annotations

import os
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass

import numpy as np
from scipy.spatial import cKDTree

from core.backends import gmsh as gmsh_backend
from core.backends.certify import why_not_delaunay, why_not_locally_delaunay
from core.backends.facets import paired
from core.backends.gmsh_half import GmshHalf
from core.backends.restore import boundary_facets, joined, outside
from core.build.delaunay import Triangulation, compacted, delaunay_cells, regular_cells
from core.errors import InputError
from core.geometry.circumspheres import CACHE_CHUNK, centre_terms, circumspheres, edge_vectors
from core.geometry.power import orthospheres
from core.parallel import in_unsplit
from core.tolerances import ILL_CONDITIONED_RTOL, SPLIT_EMPTY_RTOL

#: From this many points the Qhull backend triangulates in two halves, on two threads: it
#: gains where a second core is free (bench_weighted measures it against one Qhull call).
SPLIT_FROM_POINTS = 50_000


#: From this many points the gmsh backend triangulates in two halves, one in a child process
#: (its start costs about 0.4 s of the other core; gmsh takes some 1 s per 100k points). At
#: 200k one call was as fast with a fifth less CPU; from 350k the halves were faster
#: (benchmarks/experiments/backend_thresholds.py).
GMSH_SPLIT_FROM_POINTS = 350_000
KD_LEAF = 64  # points per leaf of the other half's tree: big spheres search faster


def worth_splitting(n_points: int, backend: str = "qhull") -> bool:
    """Whether `backend` should triangulate `n_points` points in halves: enough of them, a
    second CPU this process may run on, and the caller not in an unsplit job (one whose
    second core is taken: core.parallel.unsplit)."""
    if in_unsplit():
        return False
    try:
        cpus = len(os.sched_getaffinity(0))
    except AttributeError:  # not on Linux
        cpus = os.cpu_count() or 1
    least = GMSH_SPLIT_FROM_POINTS if backend == "gmsh" else SPLIT_FROM_POINTS
    return n_points >= least and cpus >= 2


@dataclass(frozen=True)
class _Half:
    """One half's cells kept as cells of the whole triangulation (empty of the other half)
    in point ids (rows ascending), their neighbour rows among the kept cells (-1 = none, or
    a cell not kept), their mirror (facets.paired; None when not known) and the half's
    points its own triangulation left out (Qhull: hidden or dropped)."""

    cells: np.ndarray
    nbrs: np.ndarray
    mirror: np.ndarray | None
    out: np.ndarray


def subset_cells(points: np.ndarray, weights: np.ndarray | None, ids: np.ndarray
           ) -> tuple[np.ndarray, np.ndarray]:
    """Qhull's cells of points[ids] (weighted: regular) in point ids, and their neighbours
    (each half's and the band's triangulation)."""
    if weights is None:
        cells, nbrs = delaunay_cells(points[ids])
    else:
        cells, nbrs = regular_cells(points[ids], weights[ids])
    return ids[cells].astype(np.int32), nbrs  # ids ascending: rows stay ascending


def _solved(points: np.ndarray, weights: np.ndarray | None, part: np.ndarray
            ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Centres (n, d), powers (radii² without weights) and shapes (|det| over the product of
    the edge lengths: 0 flat .. 1) of (n, d+1) cells, by Cramer's rule
    (core.geometry.circumspheres.centre_terms: the centre c solves 2 e_i . c = |e_i|² - (w_i -
    w_0))."""
    vec = edge_vectors(points, part)
    rhs, w0 = None, 0.0
    if weights is not None:
        w0 = np.take(weights, part[:, 0])
        rhs = np.einsum("nid,nid->ni", vec, vec) - (np.take(weights, part[:, 1:]) - w0[:, None])
    terms = centre_terms(vec, rhs)
    c0 = terms.num * (0.5 / np.where(terms.det != 0, terms.det, 1.0))[:, None]
    shape = np.abs(terms.det) / np.where(terms.scale > 0, terms.scale, 1.0)
    return np.take(points, part[:, 0], axis=0) + c0, np.einsum("nd,nd->n", c0, c0) - w0, shape


def _spheres(points: np.ndarray, weights: np.ndarray | None, cells: np.ndarray
             ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Centres (t, d), radii² (weighted: powers, |c - p|² - w_p of a vertex) and (t,) bool
    flags of the cells whose sphere is well defined: the plain solve on well-shaped cells,
    core.geometry.circumspheres's / core.geometry.power's careful one (extended precision) on the
    others."""
    centres = np.empty((len(cells), points.shape[1]))
    size = np.empty(len(cells))
    poor = np.empty(len(cells), dtype=bool)
    for lo in range(0, len(cells), CACHE_CHUNK):
        hi = min(lo + CACHE_CHUNK, len(cells))
        centres[lo:hi], size[lo:hi], shape = _solved(points, weights, cells[lo:hi])
        poor[lo:hi] = shape <= ILL_CONDITIONED_RTOL
    ok = ~poor
    rows = np.flatnonzero(poor)
    if len(rows):
        if weights is None:
            c0, size[rows], _, bad = circumspheres(points, cells[rows])
        else:
            c0, size[rows], _, bad = orthospheres(points, weights, cells[rows])
        centres[rows] = points[cells[rows, 0]] + c0
        ok[rows] = ~bad
    return centres, size, ok


def _keep(points: np.ndarray, weights: np.ndarray | None, cells: np.ndarray,
          other: np.ndarray, axis: int, ahead: bool) -> np.ndarray:
    """(t,) bool: the cells found empty of points[other], which lie beyond the cells'
    half along `axis` (ahead: at larger coordinates)."""
    centres, size, ok = _spheres(points, weights, cells)
    coords = points[other, axis]
    gap = coords.min() - centres[:, axis] if ahead else centres[:, axis] - coords.max()
    wmax = 0.0 if weights is None else float(weights[other].max())
    # a point q beyond the gap has power |c - q|² - w_q >= gap² - wmax to the sphere
    reach = size + wmax
    ask = ok & (reach >= 0) & ((gap <= 0) | (gap * gap <= reach * (1 + SPLIT_EMPTY_RTOL)))
    keep = ok.copy()
    if ask.any():
        lifted = points[other]
        if weights is not None:  # |(c, 0) - (q, √(wmax - w_q))|² - wmax = power of q
            lifted = np.column_stack((lifted, np.sqrt(wmax - weights[other])))
        asked = centres[ask]
        if weights is not None:
            asked = np.column_stack((asked, np.zeros(len(asked))))
        dist, _ = cKDTree(lifted, leafsize=KD_LEAF).query(asked, k=1)
        power = dist * dist - wmax
        keep[ask] = power - size[ask] > SPLIT_EMPTY_RTOL * (dist * dist + np.abs(size[ask]))
    return keep


def _only_kept(cells: np.ndarray, nbrs: np.ndarray, mirror: np.ndarray | None,
               keep: np.ndarray, out: np.ndarray) -> _Half:
    """The kept cells of a half with their neighbour table renumbered (-1 across every
    facet to a cell that was not kept, and the mirror there too)."""
    new_id = np.full(len(keep) + 1, -1, dtype=np.int32)  # [-1] -> -1
    new_id[:-1][keep] = np.arange(int(keep.sum()), dtype=np.int32)
    kept_nbrs = new_id[nbrs[keep]]
    kept_mirror = None
    if mirror is not None:
        kept_mirror = np.where(kept_nbrs >= 0, mirror[keep], -1).astype(np.int8)
    return _Half(cells[keep], kept_nbrs, kept_mirror, out)


def _half(points: np.ndarray, weights: np.ndarray | None, ids: np.ndarray,
          other: np.ndarray, axis: int, ahead: bool) -> _Half:
    """Qhull's triangulation of points[ids]; the cells found empty of points[other], which
    lie beyond ids along `axis` (ahead: at larger coordinates)."""
    cells, nbrs = subset_cells(points, weights, ids)
    in_half = np.zeros(len(points), dtype=bool)
    in_half[cells.ravel()] = True
    out = ids[~in_half[ids]]
    return _only_kept(cells, nbrs, None, _keep(points, weights, cells, other, axis, ahead), out)


def gmsh_half(points: np.ndarray, ids: np.ndarray, other: np.ndarray, axis: int,
              ahead: bool) -> _Half | str:
    """gmsh's triangulation of points[ids] (unweighted), the cells found empty of
    points[other] kept, every facet between two kept cells certified locally Delaunay
    (gmsh's cells are checked, never trusted); or the reason it cannot be used. The cells
    gmsh dropped near its half's hull are not kept: the band restores them."""
    local = gmsh_backend.gmsh_cells(points[ids])
    if not len(local):
        return "gmsh found no cell in a half"
    nbrs, mirror, manifold = paired(local, len(ids))
    if not manifold:
        return "a facet is in three cells of a half"
    cells = np.take(ids, local).astype(np.int32)  # ids ascending: rows stay ascending
    del local
    keep = _keep(points, None, cells, other, axis, ahead)
    half = _only_kept(cells, nbrs, mirror, keep, np.empty(0, dtype=np.int64))
    del cells, nbrs, mirror, keep
    reason = why_not_locally_delaunay(points, half.cells, half.nbrs, half.mirror)
    return reason or half


def _kept(halves: tuple[_Half, _Half]) -> tuple[np.ndarray, np.ndarray, np.ndarray | None]:
    """The kept cells of both halves, their neighbour table (the halves' own, the second
    renumbered after the first) and mirror (None unless both halves know theirs)."""
    first, second = halves
    shift = np.where(second.nbrs >= 0, np.int32(len(first.cells)), np.int32(0))
    mirror = None
    if first.mirror is not None and second.mirror is not None:
        mirror = np.concatenate((first.mirror, second.mirror))
    return (np.concatenate((first.cells, second.cells)),
            np.concatenate((first.nbrs, second.nbrs + shift)), mirror)


def _matched_across(cells: np.ndarray, nbrs: np.ndarray, mirror: np.ndarray | None, m: int
                    ) -> tuple[np.ndarray, np.ndarray | None, np.ndarray, bool]:
    """`nbrs` (and `mirror`, when known) with the open facets that kept cells of the two
    halves share matched (only cells with an open facet are matched), the (t,) bool cells
    that gained a neighbour, and whether no facet is in three cells."""
    edge = np.flatnonzero((nbrs < 0).any(axis=1))
    local, back, manifold = paired(cells[edge], m)
    fill = (nbrs[edge] < 0) & (local >= 0)
    nbrs = nbrs.copy()
    nbrs[edge] = np.where(fill, edge[np.maximum(local, 0)], nbrs[edge])
    if mirror is not None:
        mirror = mirror.copy()
        mirror[edge] = np.where(fill, back, mirror[edge])
    gained = np.zeros(len(cells), dtype=bool)
    gained[edge[fill.any(axis=1)]] = True
    return nbrs, mirror, gained, manifold


def _band(points: np.ndarray, weights: np.ndarray | None, cells: np.ndarray,
          nbrs: np.ndarray, hidden: np.ndarray) -> np.ndarray:
    """The cells missing from the kept union (`outside`): of the triangulation of its
    boundary vertices and the points in no kept cell; points that triangulation hides are
    added to `hidden` (hidden among some points = hidden among all)."""
    outer, behind = boundary_facets(cells, nbrs)
    covered = np.zeros(len(points), dtype=bool)
    covered[cells.ravel()] = True
    band = np.union1d(np.unique(outer), np.flatnonzero(~covered & ~hidden))
    simplices, around = subset_cells(points, weights, band)
    seen = np.zeros(len(points), dtype=bool)
    seen[simplices.ravel()] = True
    hidden[band[~seen[band]]] = True
    return outside(points, cells, outer, behind, simplices, around)


def _halves(points: np.ndarray, weights: np.ndarray | None, backend: str
            ) -> tuple[_Half, _Half] | str:
    """Both halves, split at the median of the longest axis: Qhull's on two threads, gmsh's
    in two processes (this one and a child: gmsh runs one call at a time per process); or
    the reason a gmsh half cannot be used."""
    m = len(points)
    axis = int(np.argmax(np.ptp(points, axis=0)))
    order = np.argpartition(points[:, axis], m // 2)
    low, high = np.sort(order[:m // 2]), np.sort(order[m // 2:])
    if backend == "gmsh":
        return _gmsh_halves(points, low, high, axis)
    with ThreadPoolExecutor(1, thread_name_prefix="alphascoop-split") as pool:
        later = pool.submit(_half, points, weights, high, low, axis, False)
        try:
            first = _half(points, weights, low, high, axis, True)
        finally:
            second = later.result()
    return first, second


def _gmsh_halves(points: np.ndarray, low: np.ndarray, high: np.ndarray, axis: int
                 ) -> tuple[_Half, _Half] | str:
    """gmsh_half of `low` here and of `high` in a child process (GmshHalf), at once."""
    try:
        child = GmshHalf.start(points, high, low, axis, False)
    except OSError as error:
        return f"no process for the second half ({error})"
    try:
        first = gmsh_half(points, low, high, axis, True)
        if isinstance(first, str):
            child.stop()
            return first
        second = child.result()
    except BaseException:  # Ctrl-C, out of memory: the child goes too
        child.stop()
        raise
    if isinstance(second, str):
        return second
    if not _fits(second, len(points), points.shape[1] + 1):
        return "the second half's process sent cells that do not fit"
    none = np.empty(0, dtype=np.int64)
    return first, _Half(second["cells"], second["nbrs"], second["mirror"], none)


def _fits(arrays: dict[str, np.ndarray], m: int, width: int) -> bool:
    """Whether a half's arrays from its process are (t, width) int32 cells of the m points
    with their int32 neighbour rows and int8 mirror (cheap: the join's check does the rest)."""
    cells, nbrs, mirror = (arrays.get(name) for name in ("cells", "nbrs", "mirror"))
    if cells is None or nbrs is None or mirror is None:
        return False
    if cells.ndim != 2 or cells.shape[1] != width or not len(cells) or not (
            cells.dtype == nbrs.dtype == np.int32 and mirror.dtype == np.int8
            and nbrs.shape == mirror.shape == cells.shape):
        return False
    return bool(0 <= cells.min() and cells.max() < m and -1 <= nbrs.min()
                and nbrs.max() < len(cells) and -1 <= mirror.min() and mirror.max() < width)


def split_triangulation(points: np.ndarray, weights: np.ndarray | None = None,
                        backend: str = "qhull") -> Triangulation | str:
    """The Delaunay triangulation of (m, d) distinct, well-scaled points (regular, with
    (m,) weights: Qhull only) made in two halves at once by `backend` ("qhull": Qhull's,
    the same cells as one Qhull call on all points; "gmsh": certified as the unique
    Delaunay triangulation, core.backends.certify), or the reason it cannot promise that
    (the caller then triangulates in one call)."""
    m, d = points.shape
    if m // 2 < d + 2:
        return "too few points to split"
    try:
        halves = _halves(points, weights, backend)
        if isinstance(halves, str):
            return halves
        out = np.concatenate([half.out for half in halves])
        if weights is None and len(out):
            return f"Qhull left {len(out)} points of a half out"
        hidden = np.zeros(m, dtype=bool)
        hidden[out] = True  # hidden in a half: hidden among all points
        cells, nbrs, mirror = _kept(halves)
        del halves  # the halves' own arrays: the kept ones are joined from here
        if not len(cells):
            return "no cell of a half is found empty of the other half"
        nbrs, mirror, near, manifold = _matched_across(cells, nbrs, mirror, m)
        if not manifold:
            return "a facet is in three kept cells"
        extra = _band(points, weights, cells, nbrs, hidden)
    except InputError as exc:
        return str(exc)
    cells, nbrs, mirror, manifold = joined(points, cells, nbrs, extra, mirror)
    if not manifold:
        return "a facet is in three cells after the band was restored"
    near = np.concatenate((near, np.ones(len(extra), dtype=bool)))
    reason = why_not_delaunay(points, cells, nbrs, weights=weights,
                              hidden=None if weights is None else hidden, near=near,
                              mirror=mirror)
    if reason:
        return reason
    if weights is None:
        every = np.arange(m, dtype=np.int64)
        return Triangulation(cells, nbrs, every, every.copy(), mirror)
    return compacted(cells, nbrs, m)

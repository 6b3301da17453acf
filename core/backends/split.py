"""Qhull's triangulation in two halves at once (Qhull releases the GIL), joined exactly.

The points are split at the median of their longest axis and both halves are triangulated
at the same time on two threads (Delaunay; regular for weighted points). A half's cell whose
circumsphere (orthosphere) a float test with a margin (SPLIT_EMPTY_RTOL) finds empty of the
other half's points is kept as a cell of the whole triangulation. The band the kept cells
leave around the split is restored as core.backends.restore restores gmsh's dropped cells:
the triangulation of the kept union's boundary vertices and of the points in no kept cell,
flooded from that boundary. The joined result is then checked (core.backends.certify): a
triangulation of the hull, and every facet of a cell near the join locally Delaunay
(regular) by a margin. A cell kept by mistake cannot pass: by the Delaunay lemma a
triangulation that is not Delaunay has a locally non-Delaunay facet, and the facets inside
one half are Qhull's own, so that facet lies at the join, where it is checked. The result is
thus trusted exactly as far as one Qhull call is; on any doubt the caller makes that call.
"""

from __future__ import annotations

import os
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass

import numpy as np
from scipy.spatial import cKDTree

from ..delaunay import Triangulation, compacted, delaunay_cells, regular_cells
from ..errors import InputError
from ..geometry import CACHE_CHUNK, centre_terms, circumspheres, edge_vectors
from ..power import orthospheres
from ..tolerances import ILL_CONDITIONED_RTOL, SPLIT_EMPTY_RTOL
from .certify import why_not_delaunay
from .facets import neighbours
from .restore import boundary_facets, joined, outside

#: From this many points the Qhull backend triangulates in two halves. With a free second
#: core the halves take about 0.5-0.6x one call (200k weighted, 400k 2D); on a machine whose
#: cores are all busy the split costs 10-20 % more (benchmarks/README.md).
SPLIT_FROM_POINTS = 50_000


def worth_splitting(n_points: int) -> bool:
    """Whether to triangulate `n_points` points in halves: enough of them, and a second CPU
    this process may run on."""
    try:
        cpus = len(os.sched_getaffinity(0))
    except AttributeError:  # not on Linux
        cpus = os.cpu_count() or 1
    return n_points >= SPLIT_FROM_POINTS and cpus >= 2


@dataclass(frozen=True)
class _Half:
    """One half's cells in point ids (rows ascending), their neighbour rows (-1 = none),
    and which are kept as cells of the whole triangulation (empty of the other half)."""

    cells: np.ndarray
    nbrs: np.ndarray
    keep: np.ndarray


def _cells(points: np.ndarray, weights: np.ndarray | None, ids: np.ndarray
           ) -> tuple[np.ndarray, np.ndarray]:
    """Qhull's cells of points[ids] (weighted: regular) in point ids, and their neighbours."""
    if weights is None:
        cells, nbrs = delaunay_cells(points[ids])
    else:
        cells, nbrs = regular_cells(points[ids], weights[ids])
    return ids[cells].astype(np.int32), nbrs  # ids ascending: rows stay ascending


def _solved(points: np.ndarray, weights: np.ndarray | None, part: np.ndarray
            ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Centres (n, d), powers (radii² without weights) and shapes (|det| over the product of
    the edge lengths: 0 flat .. 1) of (n, d+1) cells, by Cramer's rule
    (core.geometry.centre_terms: the centre c solves 2 e_i . c = |e_i|² - (w_i - w_0))."""
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
    core.geometry's / core.power's careful one (extended precision) on the others."""
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


def _half(points: np.ndarray, weights: np.ndarray | None, ids: np.ndarray,
          other: np.ndarray, axis: int, ahead: bool) -> _Half:
    """Triangulate points[ids]; keep the cells found empty of points[other], which lie
    beyond ids along `axis` (ahead: at larger coordinates)."""
    cells, nbrs = _cells(points, weights, ids)
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
        dist, _ = cKDTree(lifted).query(asked, k=1)
        power = dist * dist - wmax
        keep[ask] = power - size[ask] > SPLIT_EMPTY_RTOL * (dist * dist + np.abs(size[ask]))
    return _Half(cells, nbrs, keep)


def _kept(halves: tuple[_Half, _Half]) -> tuple[np.ndarray, np.ndarray]:
    """The kept cells of both halves and their neighbour table: the halves' own tables
    renumbered, -1 across every facet to a cell that was not kept."""
    cells, nbrs, start = [], [], 0
    for half in halves:
        new_id = np.full(len(half.keep) + 1, -1, dtype=np.int32)  # [-1] -> -1
        new_id[:-1][half.keep] = start + np.arange(int(half.keep.sum()), dtype=np.int32)
        cells.append(half.cells[half.keep])
        nbrs.append(new_id[half.nbrs[half.keep]])
        start += int(half.keep.sum())
    return np.concatenate(cells), np.concatenate(nbrs)


def _matched_across(cells: np.ndarray, nbrs: np.ndarray, m: int
                    ) -> tuple[np.ndarray, np.ndarray, bool]:
    """`nbrs` with the open facets that kept cells of the two halves share matched (only
    cells with an open facet are matched), the (t,) bool cells that gained a neighbour,
    and whether no facet is in three cells."""
    edge = np.flatnonzero((nbrs < 0).any(axis=1))
    local, manifold = neighbours(cells[edge], m)
    fill = (nbrs[edge] < 0) & (local >= 0)
    nbrs = nbrs.copy()
    nbrs[edge] = np.where(fill, edge[np.maximum(local, 0)], nbrs[edge])
    gained = np.zeros(len(cells), dtype=bool)
    gained[edge[fill.any(axis=1)]] = True
    return nbrs, gained, manifold


def _band(points: np.ndarray, weights: np.ndarray | None, cells: np.ndarray,
          nbrs: np.ndarray, hidden: np.ndarray) -> np.ndarray:
    """The cells missing from the kept union (`outside`): of the triangulation of its
    boundary vertices and the points in no kept cell; points that triangulation hides are
    added to `hidden` (hidden among some points = hidden among all)."""
    outer, behind = boundary_facets(cells, nbrs)
    covered = np.zeros(len(points), dtype=bool)
    covered[cells.ravel()] = True
    band = np.union1d(np.unique(outer), np.flatnonzero(~covered & ~hidden))
    simplices, around = _cells(points, weights, band)
    seen = np.zeros(len(points), dtype=bool)
    seen[simplices.ravel()] = True
    hidden[band[~seen[band]]] = True
    return outside(points, cells, outer, behind, simplices, around)


def _halves(points: np.ndarray, weights: np.ndarray | None) -> tuple[_Half, _Half]:
    """Both halves, split at the median of the longest axis, triangulated on two threads."""
    m = len(points)
    axis = int(np.argmax(np.ptp(points, axis=0)))
    order = np.argpartition(points[:, axis], m // 2)
    low, high = np.sort(order[:m // 2]), np.sort(order[m // 2:])
    with ThreadPoolExecutor(1, thread_name_prefix="alphascoop-split") as pool:
        later = pool.submit(_half, points, weights, high, low, axis, False)
        try:
            first = _half(points, weights, low, high, axis, True)
        finally:
            second = later.result()
    return first, second


def split_triangulation(points: np.ndarray, weights: np.ndarray | None = None
                        ) -> Triangulation | str:
    """Qhull's Delaunay triangulation of (m, d) distinct, well-scaled points (regular, with
    (m,) weights) made in two halves on two threads, or the reason it cannot promise the
    same cells as one Qhull call on all points (the caller then makes that call)."""
    m, d = points.shape
    if m // 2 < d + 2:
        return "too few points to split"
    try:
        halves = _halves(points, weights)
        in_half = np.zeros(m, dtype=bool)
        for half in halves:
            in_half[half.cells.ravel()] = True
        if weights is None and not in_half.all():
            return f"Qhull left {int(np.count_nonzero(~in_half))} points of a half out"
        hidden = ~in_half  # hidden in a half: hidden among all points
        cells, nbrs = _kept(halves)
        del halves  # the halves' full tables: only the kept cells are needed from here
        if not len(cells):
            return "no cell of a half is found empty of the other half"
        nbrs, near, manifold = _matched_across(cells, nbrs, m)
        if not manifold:
            return "a facet is in three kept cells"
        extra = _band(points, weights, cells, nbrs, hidden)
    except InputError as exc:
        return str(exc)
    cells, nbrs, _, manifold = joined(points, cells, nbrs, extra)
    if not manifold:
        return "a facet is in three cells after the band was restored"
    near = np.concatenate((near, np.ones(len(extra), dtype=bool)))
    reason = why_not_delaunay(points, cells, nbrs, weights=weights,
                              hidden=None if weights is None else hidden, near=near)
    if reason:
        return reason
    if weights is None:
        every = np.arange(m, dtype=np.int64)
        return Triangulation(cells, nbrs, every, every.copy())
    return compacted(cells, nbrs, m)

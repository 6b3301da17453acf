"""Triangulation backends: Qhull (scipy, always there), gmsh (optional, faster) and geogram
(regular triangulations, compiled at install).

`delaunay(points, backend)` returns Qhull's Delaunay triangulation, made by gmsh where gmsh
is installed and its result is certainly the same cells (core.backends.certify), else by
Qhull; which one did it is returned beside it. `regular(points, weights)` returns the regular
triangulation made by geogram (exact predicates, core.backends.geogram) where its library was
built, else by Qhull. Qhull works on two halves at once on larger inputs
(core.backends.split), or in one call where the halves cannot promise the same cells.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import partial

import numpy as np

from core.backends import geogram
from core.backends import gmsh as gmsh_backend
from core.backends import split as split_backend
from core.backends.certify import why_not_delaunay, why_not_locally_delaunay
from core.backends.facets import paired
from core.backends.restore import restored
from core.build.delaunay import Triangulation, compacted, regular_triangulate, triangulate
from core.errors import InputError
from core.parallel import PASSES, both, halves

BACKENDS = ("qhull", "gmsh")

#: Below this many points the automatic choice is Qhull: it is as fast there.
GMSH_FROM_POINTS = 20_000


@dataclass(frozen=True)
class Choice:
    """Which backend made a triangulation, and why gmsh was not used where it was asked."""

    backend: str  # "qhull" | "gmsh" | "geogram" (regular triangulations)
    note: str = ""  # "" or why gmsh (geogram) was not used, and why it was not split


def check_backend(backend: object) -> str | None:
    """`backend` validated: "qhull", "gmsh" or None (automatic); InputError otherwise, and
    for "gmsh" when the optional package is missing."""
    if backend is None:
        return None
    if backend not in BACKENDS:
        raise InputError(f"backend must be one of {', '.join(BACKENDS)} or None (automatic), "
                         f"not {backend!r}")
    if backend == "gmsh" and not gmsh_backend.installed():
        raise InputError("backend 'gmsh' needs the optional gmsh package (GPL): "
                         "pip install 'alphascoop[fast]', or use backend='qhull'")
    return str(backend)


def _by_gmsh(points: np.ndarray) -> tuple[Triangulation | str, str]:
    """gmsh's triangulation completed and certified, or the reason it cannot be used; and
    why it was not made in two halves ("" when it was, or was not tried). Large inputs are
    triangulated in two halves at once (core.backends.split: one in a child process), else
    (or where the halves fail) in one call (_by_gmsh_whole)."""
    if not split_backend.worth_splitting(len(points), "gmsh"):
        return _by_gmsh_whole(points), ""
    tri = split_backend.split_triangulation(points, None, "gmsh")
    if isinstance(tri, Triangulation):
        return tri, ""
    return _by_gmsh_whole(points), f"not split in two halves: {tri}"


def _by_gmsh_whole(points: np.ndarray) -> Triangulation | str:
    """gmsh's triangulation completed and certified, or the reason it cannot be used. Its
    own cells are checked locally (every inner facet) on one thread while the cells it
    dropped near the hull are restored on the other (Qhull on the boundary vertices, one
    thread); then the facets of the restored and relinked cells, and the global checks."""
    own = gmsh_backend.gmsh_cells(points)
    if not len(own):
        return "gmsh found no cell (too few points?)"
    nbrs, back, manifold = paired(own, len(points))
    if not manifold:
        return "a facet is in three cells"
    (cells, whole, mirror, manifold), reason = both(
        partial(restored, points, own, nbrs, back),
        partial(why_not_locally_delaunay, points, own, nbrs, back))
    if not manifold:
        return "a facet is in three cells"
    if reason:
        return reason
    near = np.ones(len(cells), dtype=bool)  # the restored cells and those relinked to them
    _relinked(whole, nbrs, near)
    reason = why_not_delaunay(points, cells, whole, near=near)
    if reason:
        return reason
    vertex_of_point = np.arange(len(points), dtype=np.int64)
    return Triangulation(cells, whole, vertex_of_point, vertex_of_point.copy(), mirror)


def _relinked(whole: np.ndarray, own: np.ndarray, out: np.ndarray) -> None:
    """out[:len(own)] = whether each row of the neighbour table `own` differs from its row
    in `whole` (one compare per column, the rows in halves)."""
    def part(lo: int, hi: int) -> None:
        mine = out[lo:hi]
        np.not_equal(whole[lo:hi, 0], own[lo:hi, 0], out=mine)
        for c in range(1, own.shape[1]):
            mine |= whole[lo:hi, c] != own[lo:hi, c]

    halves(part, len(own), PASSES)


def delaunay(points: np.ndarray, backend: str | None = None) -> tuple[Triangulation, Choice]:
    """The Delaunay triangulation of (m, d) distinct, well-scaled points by `backend`
    ("qhull", "gmsh" or None = gmsh where installed and m >= GMSH_FROM_POINTS).

    gmsh is used only when its cells are certainly Qhull's; otherwise the automatic choice
    falls back to Qhull (the reason in Choice.note) and a forced "gmsh" is an InputError.
    """
    backend = check_backend(backend)
    auto = backend is None and gmsh_backend.installed() and len(points) >= GMSH_FROM_POINTS
    if backend == "gmsh" or auto:
        tri, unsplit = _by_gmsh(points)
        if isinstance(tri, Triangulation):
            return tri, Choice("gmsh", unsplit)
        if backend == "gmsh":
            raise InputError(f"the gmsh backend cannot promise Qhull's exact triangulation "
                             f"of these points ({tri}); use backend='qhull' or None")
        return _by_qhull(points, None, "; ".join(filter(None, (f"gmsh not used: {tri}",
                                                                 unsplit))))
    return _by_qhull(points, None)


def regular(points: np.ndarray, weights: np.ndarray,
            backend: str | None = None) -> tuple[Triangulation, Choice]:
    """The regular triangulation of (m, d) distinct, well-scaled points with (m,) weights
    (hidden points map to -1): geogram's in one call (exact, on the calling thread) where its
    library was built and `backend` is not "qhull", else Qhull's (the reason in
    Choice.note where geogram failed)."""
    note = ""
    if backend != "qhull" and geogram.available():
        try:
            cells, neighbors = geogram.regular_cells(points, weights)
            return compacted(cells, neighbors, len(points)), Choice("geogram")
        except geogram.GeogramError as exc:
            note = f"geogram not used: {exc}"
    return _by_qhull(points, weights, note)


def _by_qhull(points: np.ndarray, weights: np.ndarray | None,
              note: str = "") -> tuple[Triangulation, Choice]:
    """Qhull's triangulation (regular, with weights): in two halves on two threads from
    split.SPLIT_FROM_POINTS points on where a second CPU is there, else (or where the
    halves cannot promise the same cells: the reason joins the note) in one call."""
    if split_backend.worth_splitting(len(points)):
        tri = split_backend.split_triangulation(points, weights)
        if isinstance(tri, Triangulation):
            return tri, Choice("qhull", note)
        note = "; ".join(filter(None, (note, f"not split in two halves: {tri}")))
    whole = triangulate(points) if weights is None else regular_triangulate(points, weights)
    return whole, Choice("qhull", note)

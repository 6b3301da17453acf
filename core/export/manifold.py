"""Split the regularized 3D boundary where the shape touches itself, so it is a 2-manifold.

Around a non-manifold edge the solid forms several wedges of cells; the two boundary faces of
one wedge are glued, the others kept apart. Then every vertex is copied once per fan of faces
glued around it. Both steps are connected components of sparse graphs (no Python loops).
Where that still leaves an edge with more than two faces (a fan meets the edge twice), the
edge is glued across the empty wedges instead, and for the rare edges still left, the other
pairings of its outgoing and incoming faces are tried one by one.
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass, field

import numpy as np
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components

from core.arrays import first_cofaces
from core.errors import AlphaScoopError

MAX_ROUNDS = 6  # gluing choices per edge are revised at most this often
MAX_REMATCH_TRIES = 24  # gluings tried per edge still bad after that
MAX_REMATCH_TOTAL = 64  # and in all (each try is one pass over the surface)


@dataclass(frozen=True)
class ManifoldReport:
    """What splitting changed: non-manifold edges and vertices found, vertex copies added."""

    nonmanifold_edges: int
    nonmanifold_vertices: int
    vertices_added: int
    unresolved_edges: int = 0
    #: (p,) int64 rows of ac.points written more than once (the pinch points split apart:
    #: a tool that merges duplicate vertices joins them again), and (p,) int64 copies of each
    split_points: np.ndarray = field(default_factory=lambda: np.zeros(0, np.int64),
                                     compare=False, repr=False)
    split_copies: np.ndarray = field(default_factory=lambda: np.zeros(0, np.int64),
                                     compare=False, repr=False)

    def line(self) -> str:
        """One-line summary for the CLI and the app."""
        if not (self.nonmanifold_edges or self.nonmanifold_vertices):
            return "surface is already a 2-manifold: nothing split"
        text = (f"split {self.nonmanifold_edges} non-manifold edges and "
                f"{self.nonmanifold_vertices} non-manifold vertices "
                f"({self.vertices_added} vertex copies added)")
        if self.unresolved_edges:
            text += f"; {self.unresolved_edges} edges still have more than two faces"
        return text


def _components(n: int, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """(n,) int label of the connected component of each node of the graph with edges a-b."""
    graph = coo_matrix((np.ones(len(a), dtype=np.int8), (a, b)), shape=(n, n))
    return connected_components(graph, directed=False)[1]


def _dense(keys: np.ndarray) -> np.ndarray:
    """(n,) int64 dense ids 0..u-1 of int64 keys (sort + diff; np.unique is slow on int64)."""
    order = np.argsort(keys, kind="stable")
    srt = keys[order]
    ids = np.empty(len(keys), dtype=np.int64)
    ids[order] = np.concatenate([[0], np.cumsum(srt[1:] != srt[:-1])]) if len(keys) else []
    return ids


def _wedge_labels(ac, filled, side, rows) -> tuple[np.ndarray, np.ndarray]:
    """Edge row and wedge label of each boundary half-edge (3f+i: edge opposite corner i).

    filled: (n_cells+1,) bool, the last entry standing for the outside; side: (r,) the cell
    of each face on the filled side. Wedges are filled cells around an edge joined through
    facets whose both cells are filled.
    """
    n_edges = len(ac.simplices(1))
    edge_of = ac.face_ids(2)
    cells = ac.facet_cells().astype(np.int64)
    cells = np.where(cells < 0, len(filled) - 1, cells)
    both = np.flatnonzero(filled[cells[:, 0]] & filled[cells[:, 1]])
    link_edges = edge_of[both].astype(np.int64)  # (m, 3)
    key_a = cells[both, 0, None] * n_edges + link_edges
    key_b = cells[both, 1, None] * n_edges + link_edges
    half_edges = edge_of[rows].astype(np.int64)  # (r, 3)
    key_h = side[:, None].astype(np.int64) * n_edges + half_edges
    ids = _dense(np.concatenate([key_a.ravel(), key_b.ravel(), key_h.ravel()]))
    m = key_a.size
    label = _components(int(ids.max()) + 1, ids[:m], ids[m: 2 * m])
    return half_edges.ravel(), label[ids[2 * m:]]


def _pairs(wedge: np.ndarray) -> np.ndarray:
    """(p, 2) half-edge ids glued two by two (each wedge has exactly two boundary faces)."""
    order = np.argsort(wedge, kind="stable")
    if len(order) % 2 or np.any(wedge[order[0::2]] != wedge[order[1::2]]):
        raise AlphaScoopError("the boundary is not closed: cannot split it into a manifold")
    return order.reshape(-1, 2)


def _fans(faces, corner_vertex, wedge, n_faces) -> tuple[np.ndarray, np.ndarray]:
    """Component label of every corner after gluing, and (r, 3) faces over those labels."""
    a, b = _glued_corners(_pairs(wedge), corner_vertex)
    label = _components(len(corner_vertex), a, b)
    local = np.argmax(faces[:, :, None] == corner_vertex.reshape(-1, 3)[:, None, :], axis=2)
    return label, label[3 * np.arange(n_faces)[:, None] + local]


def _overfull_half_edges(corners: np.ndarray, n: int) -> np.ndarray:
    """(3r,) bool: half-edges (3f+i, opposite corner i) on an edge with more than two faces.

    corners: (r, 3) vertex-copy labels of each face's corners, in the same corner order as
    the half-edge ids (n = number of labels).
    """
    ends = corners[:, [1, 2, 2, 0, 0, 1]].reshape(-1, 2)  # edge opposite corner 0, 1, 2
    ends = np.sort(ends, axis=1).astype(np.int64)
    keys = ends[:, 0] * n + ends[:, 1]
    order = np.argsort(keys, kind="stable")
    srt = keys[order]
    start = np.concatenate([[True], srt[1:] != srt[:-1]])
    group = np.cumsum(start) - 1
    size = np.bincount(group)
    out = np.empty(len(keys), dtype=bool)
    out[order] = size[group] > 2
    return out


def split_nonmanifold(ac, shape) -> tuple[np.ndarray, np.ndarray, ManifoldReport]:
    """Vertex ids (v,) into ac.points and (r, 3) faces over them, manifold, oriented as given.

    Each non-manifold edge is first glued across the solid's wedges; where that still leaves
    an edge with four or more faces, it is glued across the empty wedges instead.
    """
    faces = np.asarray(shape.regular_facets, dtype=np.int64)
    if len(faces) == 0:
        return np.empty(0, np.int64), faces.reshape(0, 3), ManifoldReport(0, 0, 0)
    rows = np.asarray(shape.regular_facet_ids)
    n_cells = len(ac.simplices(3))
    filled = np.zeros(n_cells + 1, dtype=bool)
    filled[np.asarray(shape.cell_ids)] = True
    sides = ac.facet_cells()[rows].astype(np.int64)
    sides = np.where(sides < 0, n_cells, sides)
    first_in = filled[sides[:, 0]]
    solid_side = np.where(first_in, sides[:, 0], sides[:, 1])
    empty_side = np.where(first_in, sides[:, 1], sides[:, 0])
    edge, solid = _wedge_labels(ac, filled, solid_side, rows)
    _, empty = _wedge_labels(ac, ~filled, empty_side, rows)
    corner_vertex = ac.simplices(2)[rows].astype(np.int64).ravel()  # corner 3f+i -> its vertex
    use_empty = np.zeros(len(ac.simplices(1)), dtype=bool)
    for _ in range(MAX_ROUNDS):
        wedge = np.where(use_empty[edge], empty + solid.max() + 1, solid)
        label, new_faces = _fans(faces, corner_vertex, wedge, len(faces))
        bad = _overfull_half_edges(label.reshape(-1, 3), int(label.max()) + 1)  # row order
        if not bad.any():
            break
        use_empty[edge[bad]] ^= True
    if bad.any():
        wedge = _rematch(faces, corner_vertex, wedge, edge, bad)
        label, new_faces = _fans(faces, corner_vertex, wedge, len(faces))
        bad = _overfull_half_edges(label.reshape(-1, 3), int(label.max()) + 1)
    # labels 0..c-1 of connected components, each used: the first corner of each copy
    first = first_cofaces(label[:, None], int(label.max()) + 1)
    vertex_ids = corner_vertex[first]
    per_vertex = np.bincount(vertex_ids, minlength=len(ac.points))
    split = np.flatnonzero(per_vertex > 1)
    report = ManifoldReport(int(np.count_nonzero(np.bincount(edge) > 2)),
                            int(np.count_nonzero(per_vertex > 1)),
                            int(len(first) - np.count_nonzero(per_vertex)),
                            len(np.unique(edge[bad])), split, per_vertex[split])
    return vertex_ids, new_faces.astype(np.int64), report


def _rematch(faces, corner_vertex, wedge, edge, bad) -> np.ndarray:
    """Try the other gluings (outgoing to incoming half-edges) of the few edges still bad.

    An edge with six or more faces can need a gluing that is neither all-solid nor all-empty
    wedges; each candidate is kept if it lowers the number of over-full half-edges.
    """
    wedge = wedge.copy()
    next_id = int(wedge.max()) + 1
    n_bad = int(bad.sum())
    budget = MAX_REMATCH_TOTAL
    for e in np.unique(edge[bad]):
        if budget <= 0:
            break
        hs = np.flatnonzero(edge == e)
        face, corner = np.divmod(hs, 3)
        ends = np.sort(np.stack([corner_vertex[3 * face + (corner + s) % 3] for s in (1, 2)],
                                axis=1), axis=1)
        pos = [np.argmax(faces[face] == ends[:, j, None], axis=1) for j in (0, 1)]
        forward = (pos[1] - pos[0]) % 3 == 1  # the face runs low -> high along the edge
        outs, ins = hs[forward], hs[~forward]
        if len(outs) != len(ins):  # not a pairing problem this can solve
            continue
        for perm in itertools.islice(itertools.permutations(ins), min(MAX_REMATCH_TRIES, budget)):
            budget -= 1
            trial = wedge.copy()
            trial[outs] = trial[list(perm)] = next_id + np.arange(len(outs))
            label, _ = _fans(faces, corner_vertex, trial, len(faces))
            count = int(_overfull_half_edges(label.reshape(-1, 3), int(label.max()) + 1).sum())
            if count < n_bad:
                wedge, n_bad = trial, count
                next_id += len(outs)
                break
    return wedge


def _glued_corners(half: np.ndarray, corner_vertex: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Corner pairs (same vertex) joined across each glued pair of half-edges."""
    face, opposite = np.divmod(half, 3)  # half-edge 3f+i is the edge opposite corner i
    ends = [3 * face + (opposite + s) % 3 for s in (1, 2)]  # (p, 2) corner ids, both sides
    a = np.concatenate([ends[0][:, 0], ends[1][:, 0]])
    va = corner_vertex[a]
    f_other = face[:, 1]
    cand = 3 * f_other[:, None] + np.arange(3)  # (p, 3) corners of the partner face
    cand = np.concatenate([cand, cand])
    b = cand[np.arange(len(a)), np.argmax(corner_vertex[cand] == va[:, None], axis=1)]
    return a, b

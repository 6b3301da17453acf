"""Pockets of a molecule and their mouths, after Edelsbrunner, Facello and Liang, "On the
definition and the construction of pockets in macromolecules" (Discrete Applied Mathematics
88, 1998), the method of CASTp (Liang, Edelsbrunner, Woodward, Protein Science 7, 1998).

Definitions, as computed here. D is the weighted Delaunay (regular) triangulation of the atom
balls, K ⊆ D the dual complex (the weighted alpha complex at alpha² = 0; another alpha² grows
every ball to radius² w + alpha²). A tetrahedron of D not in K is *empty*.

- Orthocentre z_T of a tetrahedron T: the point with equal power to its four balls. T is
  *obtuse across* its facet f when z_T lies strictly beyond f (the barycentric coordinate of
  z_T for the vertex opposite f is negative).
- Flow: an empty T flows into its neighbour T' across f when T is obtuse across f and f is not
  in K (a triangle of K is covered by its balls: a wall). A hull facet leads to infinity. The
  power distance to the orthocentre grows along the flow, so it has no cycle; sinks are the
  empty tetrahedra that contain their orthocentre (or whose obtuse facets are walls), and
  infinity.
- Outside: the empty tetrahedra from which some flow path reaches infinity.
- The other empty tetrahedra flow only into sinks inside the molecule. Joined across their
  shared facets not in K they form *regions*: the unions of the stable manifolds (collections)
  of inner sinks that touch through open facets.
- Mouth facets of a region: its facets not in K whose other side is outside (or beyond the
  hull). A region with mouth facets is a *pocket*: empty space whose flow stays inside, open to
  the outside only through its mouths. A region without is a *void* (cavity), a bounded
  component of the complement of the union of balls.
- Mouths: the mouth facets of one pocket joined across shared edges not in K (an edge of K
  is covered by its two balls: a bridge of atoms between two openings). A mouth's `area` is the
  part of its triangles not covered by the balls' cross-sections (disk sectors at the corners
  less half-lenses at edges in K, the sector rule of `sectors` in the plane), its `perimeter`
  the length of its rim: the triangle edges bounding it, a polygon through the rim atoms'
  centres (CASTp's rim).
- A pocket's `volume` is the volume of its tetrahedra less the union of balls inside them,
  its `area` the union's surface inside them, both exact (`regions`: the sector split where
  it is exact, each tetrahedron clipped on its own elsewhere, as near the mouths where a
  ball reaches through an open triangle); its atoms the balls with a positive share of that
  area.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components

from core.molecule.flow import flow_to_infinity, inner_regions, mouth_facets
from core.molecule.regions import DualFacts, lining_atoms, region_measures


@dataclass(frozen=True, eq=False)
class Pockets:
    """Pockets largest first. cells (c,) int64 pocket of each cell (-1 = none); volume (k,),
    area (k,) float64; atoms: k arrays of ball rows lining each; mouth_pocket (m,) int64,
    mouth_area (m,), mouth_perimeter (m,) float64 per mouth; facets (f,) int64 mouth facet
    rows and facet_mouth (f,) int64 their mouth; atom_area (k, n) sparse CSR lining area of
    each ball in each pocket."""

    cells: np.ndarray
    volume: np.ndarray
    area: np.ndarray
    atoms: tuple
    mouth_pocket: np.ndarray
    mouth_area: np.ndarray
    mouth_perimeter: np.ndarray
    facets: np.ndarray
    facet_mouth: np.ndarray
    atom_area: object

    def __len__(self) -> int:
        return len(self.volume)

    def mouths(self, pocket: int) -> np.ndarray:
        """(j,) int64 mouths of one pocket."""
        return np.flatnonzero(self.mouth_pocket == pocket)


def _mouth_groups(facts: DualFacts, facets: np.ndarray, owner: np.ndarray
                  ) -> tuple[np.ndarray, int]:
    """((f,) int64 mouth of each mouth facet, count): one pocket's mouth facets joined across
    their shared edges that are not in K (an edge in K is covered: a bridge between two
    openings)."""
    f = len(facets)
    if f == 0:
        return np.zeros(0, np.int64), 0
    edges = facts.tri_edges[facets].ravel()  # (3f,)
    open_edge = ~facts.edge_in[edges]
    keys = np.repeat(owner, 3) * (int(facts.tri_edges.max()) + 1) + edges
    _, node = np.unique(keys[open_edge], return_inverse=True)
    size = f + (int(node.max()) + 1 if len(node) else 0)
    graph = coo_matrix((np.ones(len(node)), (np.repeat(np.arange(f), 3)[open_edge], f + node)),
                       shape=(size, size))
    _, comp = connected_components(graph, directed=False)
    _, label = np.unique(comp[:f], return_inverse=True)
    return label.astype(np.int64), int(label.max()) + 1


def _lens_area(d, r1, r2):
    """Area of the intersection of two disks of radii r1, r2 at distance d (they meet)."""
    a1 = np.arccos(np.clip((d * d + r1 * r1 - r2 * r2) / (2 * d * r1), -1, 1))
    a2 = np.arccos(np.clip((d * d + r2 * r2 - r1 * r1) / (2 * d * r2), -1, 1))
    k = (-d + r1 + r2) * (d + r1 - r2) * (d - r1 + r2) * (d + r1 + r2)
    return r1 * r1 * a1 + r2 * r2 * a2 - 0.5 * np.sqrt(np.maximum(k, 0.0))


def open_area(facts: DualFacts, facets: np.ndarray) -> np.ndarray:
    """(f,) float64 area of each triangle not covered by its three balls' cross-sections."""
    tri = facts.triangles[facets]
    c, r = facts.centres[tri], facts.radii[tri]
    out = 0.5 * np.linalg.norm(np.cross(c[:, 1] - c[:, 0], c[:, 2] - c[:, 0]), axis=1)
    for v in range(3):
        p, q = (c[:, w] - c[:, v] for w in range(3) if w != v)
        angle = np.arctan2(np.linalg.norm(np.cross(p, q), axis=1), np.einsum("ij,ij->i", p, q))
        out -= 0.5 * angle * r[:, v] ** 2
        a, b = (w for w in range(3) if w != v)  # the edge opposite v
        meet = facts.edge_in[facts.tri_edges[facets, v]]
        d = np.linalg.norm(c[:, a] - c[:, b], axis=1)
        out += np.where(meet, 0.5 * _lens_area(d, r[:, a], r[:, b]), 0.0)
    return out


def _rim_length(facts: DualFacts, facets: np.ndarray, mouth: np.ndarray, count: int
                ) -> np.ndarray:
    """(count,) float64 total length of the edges that bound each mouth (in one facet of it)."""
    edges = facts.tri_edges[facets].ravel()
    owner = np.repeat(mouth, 3)
    key = owner * (int(facts.tri_edges.max()) + 1) + edges
    _, first, times = np.unique(key, return_index=True, return_counts=True)
    rim = first[times == 1]
    tri = facts.triangles[facets].repeat(3, 0)
    slot = np.tile(np.arange(3), len(facets))
    a = tri[np.arange(len(tri)), (slot + 1) % 3]
    b = tri[np.arange(len(tri)), (slot + 2) % 3]
    length = np.linalg.norm(facts.centres[a] - facts.centres[b], axis=1)
    return np.bincount(owner[rim], weights=length[rim], minlength=count)


def find_pockets(facts: DualFacts) -> Pockets:
    """The pockets of the complex `facts` describes, largest volume first."""
    regions, count = inner_regions(facts, flow_to_infinity(facts))
    facets, owner = mouth_facets(facts, regions)
    open_regions = np.unique(owner)
    relabel = np.full(count + 1, -1, np.int64)
    relabel[open_regions] = np.arange(len(open_regions))
    labels = relabel[regions]
    measures = region_measures(facts, labels, len(open_regions))
    order = np.argsort(-measures.volume, kind="stable")
    rank = np.empty(len(order) + 1, np.int64)
    rank[order], rank[-1] = np.arange(len(order)), -1
    owner = rank[relabel[owner]]
    mouth, n_mouths = _mouth_groups(facts, facets, owner)
    mouth_pocket = np.zeros(n_mouths, np.int64)
    mouth_pocket[mouth] = owner
    return Pockets(
        cells=rank[labels], volume=measures.volume[order], area=measures.area[order],
        atoms=tuple(lining_atoms(measures, int(p)) for p in order),
        mouth_pocket=mouth_pocket,
        mouth_area=np.maximum(np.bincount(mouth, weights=open_area(facts, facets),
                                          minlength=n_mouths), 0.0),
        mouth_perimeter=_rim_length(facts, facets, mouth, n_mouths),
        facets=facets, facet_mouth=mouth, atom_area=measures.atom_area[order])

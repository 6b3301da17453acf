"""Exact alpha shapes at one alpha, tile by tile: scans bigger than memory.

Modules: plan (tile sizes from density and memory budget), partition (points into tiles with
their margins, in memory or streamed to per-tile files), tile (one tile's complex,
classified, owned simplices in global ids), degenerate (tiles on a line), merge (union of
the tiles, components, measures), summary (their numbers only, folded in a tile at a time),
memory (all of it in this process), sources (chunked readers; LAS/LAZ, and core.io.streams
for big text and PLY files), copc and octree (COPC files read by box through their octree
index), runner (tiles as Dask tasks, each on one core of its worker), view (the merged
shape seen by core.export).

Why the union of the tiles equals the whole complex at alpha
============================================================
Notation: S the points, K(S) the alpha complex of S at a fixed finite alpha (a2 = alpha²,
or the alpha2 asked for), C a tile's core (a box), N the core grown by the margin m on
every axis, T the tile's points: every point of S in N (and possibly more; only
S ∩ N ⊆ T ⊆ S is used). Weighted points (p, w) use the power distance |x - p|² - w;
classic points have w = 0.

1. A ball per member. A simplex s is in K(S) exactly when some coface t ⊇ s (t = s
   allowed) has its smallest orthogonal ball B_t (centre c, squared radius r² <= a2)
   empty: no point q of S with |c - q|² - w_q < r². (An unattached simplex enters with its
   own ball; an attached one enters with a coface, and following the cofaces ends at an
   unattached simplex or a cell, whose ball is empty since the triangulation is
   Delaunay/regular; conversely an empty ball makes t a Delaunay (regular) simplex with
   enter <= alpha, hence s a member.)
2. The ball is near every vertex. For a vertex v of t, |c - v|² = w_v + r² <= W + a2 (W the
   largest weight), and a point q that could violate emptiness has
   |c - q|² < w_q + r² <= W + a2. So every point that decides B_t lies within
   R = 2 sqrt(W + a2) of v (classic points: 2 alpha). The margin is m = R plus a relative
   slack of 1e-6 (plan.margin_for), so that rounding in the grid arithmetic cannot drop a
   point at distance just under R.
3. Membership is certain for simplices with a vertex in the core. Let s have a vertex
   v in C. If s ∈ K(S), its ball B_t lies within R of v, so all of t's vertices and every
   point that could be inside B_t are in N, hence in T, and B_t is empty in T: s ∈ K(T).
   If s ∈ K(T), its ball (for T) lies within R of v, so every point of S that could be in
   it is in N ⊆ T: the ball is empty in S, and s ∈ K(S). Hidden (redundant) weighted points
   are never members in either.
4. Classes are certain too. SINGULAR vs REGULAR: s is REGULAR when some cofacet of s is a
   member; every cofacet has the vertex v in C, so by 3 it is a member of K(T) exactly when
   it is a member of K(S). INTERIOR: every cell of the triangulation around s is a member
   (and s is not on the hull). If so in S, each of those cells has v and a ball within R of
   v, so each is a cell of T's triangulation and a member of K(T); they already fill a
   neighbourhood of s, so T's triangulation has no other cell around s and s is not on T's
   hull: s is INTERIOR in T. The converse is the same argument with S and T exchanged (a
   simplex on S's hull cannot get a full star of member cells in T, since those cells
   would be S's cells filling a neighbourhood of it). So every simplex with a vertex in C
   gets the same class in T as in S, and the tile also knows every value enter, regular,
   interior that is at most alpha (larger ones may differ: they are reported as NaN).
5. Each simplex is kept once. Every point lies in the core of exactly one tile (the floor
   of its grid coordinate, plan.TilePlan.core_tile). A tile keeps a member simplex when its
   lowest global vertex id (input row; duplicates take their first row, and all copies of
   a point fall in the same tiles) is one of its core points. That vertex is in the core,
   so by 3 and 4 the kept simplex and its class are the global ones; and no other tile
   keeps it. The union over tiles is K(S), simplex for simplex and class for class.
6. Ties. Cospherical points (grids, lattices of scans) have several Delaunay
   triangulations; the project's exact build picks one by a symbolic perturbation whose
   weights are a hash of each point's coordinates (core.certify.point_ties), so the tile
   and the whole set pick the same one: 1-4 hold for the perturbed points, whose
   triangulation is unique. (Weighted builds use Qhull's regular triangulation without
   that certification: exact ties there are resolved by Qhull.) Planar 3D input is
   projected on its plane once, for the whole set, exactly as the in-memory build does.
   Rounding is alike too: radii are computed from a simplex's vertices in their order in
   the build, and that order (core.build.points.canonical_order, a Morton order of each
   point's own coordinate bits) is the same in a tile as in the whole set, so congruent
   cells of a lattice, whose radii differ only by rounding, fall on the same side of alpha
   in both (power-of-two scalings, the only other difference, are exact).
7. Flat tiles. A tile whose points are all on one plane (3D) has no member cell near its
   core (any member cell would have all its vertices in T); its members are those of the
   plane's 2D complex (the same empty balls), none is INTERIOR, faces of members are
   REGULAR and triangles SINGULAR (tile.py). A tile on one line keeps the vertices and the
   neighbour edges of half length <= alpha (degenerate.py, classic points only).

Components are joined across tiles by connected components of the member edges over
global ids; volume (area) and boundary area (perimeter) are sums of the owned cells and
REGULAR facets. The check in DESIGN.md (a margin of 1 alpha is not enough) and the tests
(tests/test_tiled_*.py) compare the union with the in-memory complex simplex for simplex.
"""

from core.tiled.memory import tiled_shape
from core.tiled.merge import TiledShape

__all__ = ["TiledShape", "tiled_shape"]

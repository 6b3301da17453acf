"""Every numerical tolerance of the core, in one place; all are relative to the data's scale."""

from __future__ import annotations

#: Smallest/largest singular value of the centred points below this: the set is flat
#: (3D -> planar, built as a 2D complex; 2D -> collinear, an error).
FLAT_RTOL = 1e-9

#: A simplex whose volume-like determinant, relative to the product of its edge lengths, is
#: below this has no unique circumsphere; its sphere is then found by least squares.
DEGENERATE_RTOL = 1e-14

#: The same test for ill-conditioned simplices recomputed in extended precision (64-bit
#: mantissa): thin but genuine slivers (needles, scans) keep their own sphere.
EXTENDED_DEGENERATE_RTOL = 1e-17

#: Simplices less well-shaped than this (same measure) get their sphere recomputed in
#: extended precision: thin slivers of near-cospherical scans would lose digits otherwise.
ILL_CONDITIONED_RTOL = 1e-5

#: Cells whose |determinant| is below this times the data's extent**d are checked for folds
#: (overlapping a neighbour): float64 rounding of exactly flat groups leaves determinants
#: around 1e-16 of that, genuine cells of even huge scans stay far above it.
FOLD_CANDIDATE_RTOL = 1e-9

#: A point is strictly inside a sphere only if its power is below -ON_SPHERE_RTOL times the
#: squared distances involved: cospherical points of lattices and scans count as on the sphere.
ON_SPHERE_RTOL = 1e-13

#: A facet whose smallest sphere's radius² is within this share of its cell's (the cell's
#: centre close to the facet's plane) gets its attachment decided by an exact predicate.
NEAR_SPHERE_RTOL = 1e-6

#: A cell whose |determinant| (d! volume) is below this times r^d (r its circumradius) is
#: ill-conditioned: its flatness (orientation) is decided by an exact predicate.
SLIVER_RTOL = 1e-6

#: Simplices whose shape |det| / prod |v_i| (v_i the edge vectors from a vertex) is below
#: this may miss 1e-9 relative on r² (cells: extended precision, error ~ 2**-64 / shape;
#: triangles: float64, ~ 2**-53 / shape): their radius is computed in rational arithmetic.
EXACT_RADIUS_SHAPE = {"cell": 1e-9, "triangle": 1e-7}

#: A power |c|² - w below this share of |c|² + |w| has lost digits to cancellation: it is
#: recomputed in extended precision (values near zero must keep their relative accuracy).
POWER_CANCEL_RTOL = 1e-3

#: Below this share even extended precision keeps too few digits: the power is computed
#: exactly (rational arithmetic; rare, a handful of simplices in real data).
POWER_EXACT_RTOL = 1e-6

#: A facet of the lifted points' hull is a cell of the regular triangulation when its unit
#: outward normal points down by more than this (vertical facets are not cells).
LOWER_FACET_COS = 1e-12

#: Largest |coordinate| accepted per dimension: squared distances of points this far apart,
#: and areas (2D) or volumes (3D) of their cells, stay finite in float64 with room to spare.
MAX_COORDINATE = {2: 1e150, 3: 1e100}

#: A triangulation from another backend (gmsh) is taken as Qhull's only where every in-sphere
#: test across a facet and every cell's orientation is decided by more than this share of
#: its magnitude (the sum of the absolute terms): near-cospherical or flat groups, where
#: Qhull's own rounding picks one of several triangulations, make the build use Qhull.
BACKEND_CERTAIN_RTOL = 1e-12

#: A cell of one half (core.backends.split) is kept as a cell of the whole triangulation only
#: where the other half's nearest point has a power (squared distance) to its circumsphere
#: (orthosphere) larger than the sphere's by more than this share of the terms.
SPLIT_EMPTY_RTOL = 1e-9
#: A ball's exposed area (core.molecule.measures) below this share of its sphere's area is the
#: rounding of the inclusion-exclusion sum, whose terms are up to that area each (buried balls
#: of real molecules come out at 1e-16 to 1e-14 of it): the ball has no exposed area.
EXPOSED_AREA_RTOL = 1e-9

#: A power plane is left out of a ball's piece when its cap (the ball beyond it) lies beyond
#: another plane of the piece by more than this fraction of the ball's radius (a sure margin:
#: a plane left in changes nothing, one left out wrongly would).
CAP_BEYOND_RTOL = 1e-9

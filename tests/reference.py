"""Independent references for the interval table: gudhi, and a brute force of the definitions.

Nothing here reads the implementation's tables; the tests compare the two sides.
"""

from __future__ import annotations

import os
from itertools import combinations
from pathlib import Path

import numpy as np
import pytest

SQ_RTOL = 1e-9  # relative slack on squared radii for generic input


def canonical(simplices: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Rows sorted within, then lexicographically: ((n, k+1) int64, (n,) order into the input)."""
    rows = np.sort(np.asarray(simplices, dtype=np.int64), axis=1)
    if len(rows) == 0:
        return rows, np.zeros(0, dtype=np.int64)
    order = np.lexsort(rows.T[::-1])
    return rows[order], order


def row_keys(rows: np.ndarray, base: int) -> np.ndarray:
    """(n,) int64 keys of (n, j) int rows of values < base (rows sorted within)."""
    rows = np.asarray(rows, dtype=np.int64)
    assert float(base) ** rows.shape[1] < 2.0**62, "too many vertices for int64 keys"
    keys = np.zeros(len(rows), dtype=np.int64)
    for col in rows.T:
        keys = keys * base + col
    return keys


def cofacet_pairs(faces: np.ndarray, cofaces: np.ndarray, base: int) -> tuple:
    """(face row, coface row) incidences of sorted (n_k, k+1) faces and (n_{k+1}, k+2) cofaces."""
    k2 = cofaces.shape[1]
    drop = [np.delete(np.arange(k2), j) for j in range(k2)]
    sub = np.concatenate([cofaces[:, d] for d in drop])
    co = np.tile(np.arange(len(cofaces)), k2)
    fkeys = row_keys(faces, base)
    order = np.argsort(fkeys, kind="stable")
    skeys = row_keys(sub, base)
    pos = np.searchsorted(fkeys[order], skeys)
    pos = np.minimum(pos, len(order) - 1)
    found = fkeys[order][pos] == skeys
    assert found.all(), "a face of a simplex is missing from the complex"
    return order[pos], co


def derived_intervals(simplices: dict, enter: dict, dim: int, base: int) -> tuple[dict, dict]:
    """regular = min enter over cofacets; interior = max enter over top cofaces, inf on the hull."""
    regular = {dim: enter[dim].copy()}
    interior = {dim: enter[dim].copy()}
    for k in range(dim - 1, -1, -1):
        f, c = cofacet_pairs(simplices[k], simplices[k + 1], base)
        reg = np.full(len(simplices[k]), np.inf)
        np.minimum.at(reg, f, enter[k + 1][c])
        inter = np.full(len(simplices[k]), -np.inf)
        np.maximum.at(inter, f, interior[k + 1][c])
        if k == dim - 1:
            inter[np.bincount(f, minlength=len(reg)) == 1] = np.inf
        regular[k], interior[k] = reg, inter
    return regular, interior


def gudhi_table(points: np.ndarray, precision: str = "safe") -> dict:
    """gudhi as {k: (simplices, enter_sq, regular_sq, interior_sq)}; vertex ids = input rows."""
    import gudhi

    pts = np.asarray(points, dtype=np.float64)
    st = gudhi.AlphaComplex(points=pts, precision=precision).create_simplex_tree()
    return simplex_tree_table(st, len(pts))


def simplex_tree_table(st, n_points: int) -> dict:
    """A gudhi simplex tree as {k: (simplices, enter_sq, regular_sq, interior_sq)} plus
    "dim" and "st"; simplices canonical, regular/interior derived from the complex."""
    dim = st.dimension()
    rows = {k: [] for k in range(dim + 1)}
    vals = {k: [] for k in range(dim + 1)}
    for simplex, filt in st.get_simplices():
        rows[len(simplex) - 1].append(simplex)
        vals[len(simplex) - 1].append(filt)
    simplices, enter = {}, {}
    for k in range(dim + 1):
        arr, order = canonical(np.array(rows[k], dtype=np.int64).reshape(-1, k + 1))
        simplices[k] = arr
        enter[k] = np.array(vals[k], dtype=np.float64)[order]
    regular, interior = derived_intervals(simplices, enter, dim, n_points)
    return {"dim": dim, "st": st, **{k: (simplices[k], enter[k], regular[k], interior[k])
                                      for k in range(dim + 1)}}


def gudhi_star_intervals(st, simplex: list[int], dim: int) -> tuple[float, float]:
    """(regular_sq, interior_sq) of one simplex from gudhi's get_cofaces (slow cross-check)."""
    k = len(simplex) - 1
    if k == dim:
        f = st.filtration(simplex)
        return f, f
    cof = [v for _, v in st.get_cofaces(simplex, 1)]
    tops = [v for _, v in st.get_cofaces(simplex, dim - k)]
    on_hull = any(
        len(st.get_cofaces(facet, 1)) == 1
        for facet, _ in (st.get_cofaces(simplex, dim - 1 - k) if k < dim - 1 else [(simplex, 0)])
    )
    return min(cof), (np.inf if on_hull else max(tops))


def ours_by_input_ids(ac, k: int) -> tuple[np.ndarray, np.ndarray]:
    """Our k-simplices as canonical input-row tuples, intervals in that order (unique input)."""
    m = len(ac.points)
    n = len(ac.input_index)
    assert m == n, "comparison by input ids needs duplicate-free input"
    inv = np.empty(m, dtype=np.int64)
    inv[np.asarray(ac.input_index)] = np.arange(n)
    rows, order = canonical(inv[np.asarray(ac.simplices(k))])
    return rows, np.asarray(ac.intervals(k))[order]


def smallest_circumspheres(points: np.ndarray, simplices: np.ndarray) -> tuple:
    """Centres (n, d) and radii (n,) of the smallest spheres through each simplex's vertices.

    Closed forms relative to the first vertex in extended precision, so slivers stay accurate.
    """
    pts = np.asarray(points, dtype=np.float64)
    d = pts.shape[1]
    p3 = np.zeros((len(pts), 3), dtype=np.longdouble)
    p3[:, :d] = pts
    s = np.asarray(simplices, dtype=np.int64)
    base = p3[s[:, 0]]
    rel = [p3[s[:, j]] - base for j in range(1, s.shape[1])]
    if len(rel) == 0:
        offset = np.zeros_like(base)
    elif len(rel) == 1:
        offset = rel[0] / 2
    elif len(rel) == 2:
        a, b = rel
        axb = np.cross(a, b)
        num = np.cross(_sq(a)[:, None] * b - _sq(b)[:, None] * a, axb)
        offset = num / (2 * _sq(axb))[:, None]
    else:
        a, b, c = rel
        num = (_sq(a)[:, None] * np.cross(b, c) + _sq(b)[:, None] * np.cross(c, a)
               + _sq(c)[:, None] * np.cross(a, b))
        offset = num / (2 * np.einsum("ij,ij->i", a, np.cross(b, c)))[:, None]
    centres = (base + offset)[:, :d].astype(np.float64)
    return centres, np.sqrt(_sq(offset)).astype(np.float64)


def _sq(v: np.ndarray) -> np.ndarray:
    """(n,) squared norms of (n, 3) rows."""
    return np.einsum("ij,ij->i", v, v)


def strictly_inside(points: np.ndarray, centres: np.ndarray, radii: np.ndarray) -> np.ndarray:
    """(n,) bool: a point lies strictly inside each sphere (relative slack 1e-9 on the sphere)."""
    d2 = ((np.asarray(points)[None, :, :] - centres[:, None, :]) ** 2).sum(axis=2)
    return (d2 < (radii**2)[:, None] * (1.0 - 1e-9)).any(axis=1)


def brute_table(points: np.ndarray, simplices: dict, dim: int) -> dict:
    """Intervals by core/build/table.py's rules, top-down, with empty-ball tests on all points."""
    pts = np.asarray(points, dtype=np.float64)
    sigma, attached, enter = {}, {}, {}
    for k in range(dim + 1):
        c, r = smallest_circumspheres(pts, simplices[k])
        sigma[k], attached[k] = r, strictly_inside(pts, c, r)
    enter[dim] = sigma[dim].copy()
    for k in range(dim - 1, -1, -1):
        f, c = cofacet_pairs(simplices[k], simplices[k + 1], len(pts))
        low = np.full(len(simplices[k]), np.inf)
        np.minimum.at(low, f, enter[k + 1][c])
        enter[k] = np.where(attached[k], low, sigma[k])
    regular, interior = derived_intervals(simplices, enter, dim, len(pts))
    return {"sigma": sigma, "attached": attached, "enter": enter,
            "regular": regular, "interior": interior}


def in_complex_by_definition(simplices: dict, sigma: dict, attached: dict, dim: int,
                             alpha: float, base: int) -> dict:
    """C1/C2: T in C_alpha iff a Delaunay U ⊇ T has an empty smallest sphere, radius <= alpha."""
    inside = {k: (~attached[k] | (k == dim)) & (sigma[k] <= alpha) for k in range(dim + 1)}
    for k in range(dim, 0, -1):
        for j in range(k - 1, -1, -1):
            rows = simplices[k][inside[k]]
            if len(rows) == 0:
                break
            subs = np.concatenate([rows[:, list(c)] for c in combinations(range(k + 1), j + 1)])
            keys = row_keys(simplices[j], base)
            hit = np.isin(keys, row_keys(subs, base))
            inside[j] = inside[j] | hit
    return inside


def delaunay_simplices(points: np.ndarray) -> dict:
    """{k: canonical (n_k, k+1) int64} faces of scipy's Delaunay cells (reference self-checks)."""
    from scipy.spatial import Delaunay

    cells = Delaunay(np.asarray(points, dtype=np.float64)).simplices
    dim = cells.shape[1] - 1
    out = {}
    for k in range(dim + 1):
        subs = np.concatenate([cells[:, list(c)] for c in combinations(range(dim + 1), k + 1)])
        out[k] = np.unique(canonical(subs)[0], axis=0)
    return out


def hull_simplices(points: np.ndarray, dim: int) -> dict:
    """Faces of the convex hull facets (scipy Qhull), canonical per dimension k < dim."""
    from scipy.spatial import ConvexHull

    facets = ConvexHull(np.asarray(points, dtype=np.float64)).simplices
    out = {}
    for k in range(dim):
        subs = np.concatenate([facets[:, list(c)] for c in combinations(range(dim), k + 1)])
        rows, _ = canonical(subs)
        out[k] = np.unique(rows, axis=0)
    return out


def simplex_measures(points: np.ndarray, cells: np.ndarray) -> np.ndarray:
    """(n,) area (2D) or volume (3D) of (n, dim+1) simplices."""
    pts = np.asarray(points, dtype=np.float64)
    cells = np.asarray(cells, dtype=np.int64)
    if len(cells) == 0:
        return np.zeros(0)
    a = pts[cells[:, 1:]] - pts[cells[:, :1]]
    d = cells.shape[1] - 1
    return np.abs(np.linalg.det(a)) / (2.0 if d == 2 else 6.0)


def gudhi_measure(points: np.ndarray, table: dict, alpha: float) -> float:
    """Area/volume of gudhi's complex at alpha: top simplices with filtration <= alpha**2."""
    dim = table["dim"]
    cells = table[dim][0]
    keep = table[dim][1] <= alpha**2
    return float(simplex_measures(points, cells[keep]).sum())


# The skip reasons CI accepts (tests/skip_guard.py): the shared data's absence, only while
# the folder is absent; and a comparison with a library of the `compare` extra, which CI does
# not install (it pins matplotlib below the version the window uses).
DATA_ABSENT = "shared real-scan data absent (../shared/data or $ALPHASCOOP_DATA)"
COMPARE_EXTRA = "a comparison in the `compare` extra, which CI does not install"


def data_dir() -> Path | None:
    """The shared real-scan folder, or None when it is absent."""
    here = Path(__file__).resolve().parents[2] / "shared" / "data"
    if here.is_dir():
        return here
    env = os.environ.get("ALPHASCOOP_DATA")
    return Path(env) if env and Path(env).is_dir() else None


needs_data = pytest.mark.skipif(data_dir() is None, reason=DATA_ABSENT)


def shared_file(name: str) -> Path:
    """The shared file `name`; the test is skipped (DATA_ABSENT) when the folder is absent.
    A folder without that file is not a reason to skip: the test fails reading it."""
    folder = data_dir()
    if folder is None:
        pytest.skip(DATA_ABSENT)
    return folder / name


def read_scan(path: Path) -> np.ndarray:
    """(n, 3) float64 xyz of a scan file: core.io.read_points if present, else the libraries."""
    try:
        from core.io import read_points
    except ImportError:
        read_points = None
    if read_points is not None:
        got = read_points(path)
        pts = getattr(got, "points", got)
        return np.asarray(pts, dtype=np.float64)
    return read_scan_raw(Path(path))


def read_scan_raw(path: Path) -> np.ndarray:
    """(n, 3) float64 xyz of every record (duplicates kept) via plyfile, pypcd4 or laspy."""
    suffix = path.suffix.lower()
    if suffix == ".ply":
        from plyfile import PlyData

        v = PlyData.read(str(path))["vertex"]
        return np.column_stack([v["x"], v["y"], v["z"]]).astype(np.float64)
    if suffix == ".pcd":
        from pypcd4 import PointCloud

        return np.asarray(PointCloud.from_path(path).numpy(("x", "y", "z")), dtype=np.float64)
    import laspy

    las = laspy.read(str(path))
    return np.column_stack([las.x, las.y, las.z]).astype(np.float64)


def expected_classes(intervals: np.ndarray, alpha: float) -> np.ndarray:
    """(n,) int8 class at alpha from (n, 3) intervals, closed on the left (ARCHITECTURE.md)."""
    iv = np.asarray(intervals)
    return (iv <= alpha).sum(axis=1).astype(np.int8)


def assert_valid_table(ac) -> None:
    """Shapes, dtypes, no NaN, enter <= regular <= interior, row order, filtration (face_ids)."""
    dim, pts = ac.dim, np.asarray(ac.points)
    assert dim in (2, 3)
    assert pts.dtype == np.float64 and pts.ndim == 2 and pts.shape[1] == dim
    assert np.isfinite(pts).all()
    m = len(pts)
    srt = pts[np.lexsort(pts.T[::-1])]
    assert (np.diff(srt, axis=0) != 0).any(axis=1).all(), "duplicate points in ac.points"
    counts = []
    for k in range(dim + 1):
        s, iv = np.asarray(ac.simplices(k)), np.asarray(ac.intervals(k))
        assert s.shape == (len(s), k + 1) and np.issubdtype(s.dtype, np.integer)
        assert iv.shape == (len(s), 3) and iv.dtype == np.float64
        assert len(s) > 0 and s.min() >= 0 and s.max() < m
        assert (np.diff(s, axis=1) > 0).all(), f"rows of simplices({k}) not strictly ascending"
        keys = np.sort(row_keys(s, m))
        assert (np.diff(keys) > 0).all(), f"repeated simplices in dimension {k}"
        assert not np.isnan(iv).any(), f"NaN in intervals({k})"
        assert np.isfinite(iv[:, 0]).all() and (iv[:, 0] >= 0).all()
        assert (iv[:, 0] <= iv[:, 1]).all() and (iv[:, 1] <= iv[:, 2]).all()
        assert (np.diff(iv[:, 0]) >= 0).all(), f"simplices({k}) not ordered by enter"
        if k == dim:
            assert (iv[:, 0] == iv[:, 1]).all() and (iv[:, 0] == iv[:, 2]).all()
        else:
            assert np.isfinite(iv[:, 1]).all(), f"a {k}-simplex with no cofacet"
        counts.append(len(s))
        if k == 0:
            assert (iv[:, 0] == 0).all() and len(s) == m
        else:
            _assert_faces(ac, k, s, iv)
    euler = sum((-1) ** k * c for k, c in enumerate(counts))
    assert euler == 1, f"Euler characteristic {euler} != 1: not a triangulated convex hull"


def _assert_faces(ac, k: int, s: np.ndarray, iv: np.ndarray) -> None:
    """face_ids(k) names the faces; face enter, regular <= coface enter; interior >= coface's."""
    fid = np.asarray(ac.face_ids(k))
    faces = np.asarray(ac.simplices(k - 1))
    fiv = np.asarray(ac.intervals(k - 1))
    assert fid.shape == s.shape
    for j in range(k + 1):
        assert np.array_equal(faces[fid[:, j]], np.delete(s, j, axis=1)), "face_ids wrong"
        assert (fiv[fid[:, j], 0] <= iv[:, 0]).all(), f"filtration broken in dimension {k}"
        assert (fiv[fid[:, j], 1] <= iv[:, 0]).all(), f"face regular > coface enter ({k})"
        assert (fiv[fid[:, j], 2] >= iv[:, 2]).all(), f"interior of a face below its coface's ({k})"


def facet_measures(points: np.ndarray, facets: np.ndarray) -> np.ndarray:
    """(n,) length (2D) or area (3D) of (n, dim) facets."""
    pts = np.asarray(points, dtype=np.float64)
    f = np.asarray(facets, dtype=np.int64).reshape(-1, pts.shape[1])
    if f.shape[1] == 2:
        return np.linalg.norm(pts[f[:, 1]] - pts[f[:, 0]], axis=1)
    return np.linalg.norm(np.cross(pts[f[:, 1]] - pts[f[:, 0]], pts[f[:, 2]] - pts[f[:, 0]]),
                          axis=1) / 2


def gudhi_boundary_measure(points: np.ndarray, table: dict, alpha: float) -> float:
    """Area (3D) / length (2D) of gudhi's regular facets at alpha (one cell in the complex)."""
    dim = table["dim"]
    facets, cells = table[dim - 1][0], table[dim][0]
    f, c = cofacet_pairs(facets, cells, len(points))
    cell_in = table[dim][1] <= alpha**2
    n_in = np.bincount(f, weights=cell_in[c], minlength=len(facets))
    regular = (table[dim - 1][1] <= alpha**2) & (n_in == 1)
    return float(facet_measures(points, facets[regular]).sum())

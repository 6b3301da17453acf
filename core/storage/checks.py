"""Is a table read from a file one the queries can trust? Cheap, vectorized checks.

A saved or cached table can be damaged or crafted while its zip checksums stay valid. Every
array is checked for what the queries rely on: dtypes, shapes, index ranges, sorted orders,
enter <= regular <= interior, lengths that agree, cell measures that match the points, and
signatures that agree with the saved topology. Each check is one or two numpy passes over an
array (the whole set costs a fraction of loading it); a failure is a FileFormatError.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from core.errors import FileFormatError

MEASURE_RTOL = 1e-9  # recomputed cell measures agree with the saved ones to rounding
MEASURE_SAMPLES = 1 << 16  # cells whose measure is recomputed (spread over the table)
SAMPLES = 2048  # forest values and spectrum entries compared with the table they come from
CHUNK = 1 << 18  # cells per pass when recomputing measures (bounded temporary memory)


def spread(n: int, count: int) -> np.ndarray:
    """Up to `count` sorted row indices spread evenly over range(n), first and last included."""
    return np.unique(np.linspace(0, n - 1, min(n, count)).astype(np.int64))


class Checker:
    """Raises FileFormatError naming the file and the first array that is wrong; `subject`
    says what the file failed to be ("{path}: not {subject} ({what})")."""

    def __init__(self, path: Path, subject: str = "a valid Alpha Scoop table") -> None:
        self.path, self.subject = path, subject

    def that(self, condition: object, what: str) -> None:
        """Fail with `what` unless condition holds."""
        if not bool(condition):
            raise self.error(what)

    def error(self, what: str) -> FileFormatError:
        """The error for this file failing with `what`."""
        return FileFormatError(f"{self.path}: not {self.subject} ({what})")

    def array(self, arr: np.ndarray, name: str, dtype: type, shape: tuple) -> np.ndarray:
        """arr has exactly `dtype` and `shape` (None in shape: any length)."""
        self.that(isinstance(arr, np.ndarray) and arr.dtype == dtype,
                  f"{name} must be {np.dtype(dtype).name}")
        self.that(arr.ndim == len(shape) and all(
            want is None or want == got for want, got in zip(shape, arr.shape, strict=True)),
            f"{name} has shape {arr.shape}")
        return arr

    def ids(self, arr: np.ndarray, name: str, low: int, high: int) -> None:
        """Every entry of the integer array lies in [low, high)."""
        self.that(arr.size == 0 or (int(arr.min()) >= low and int(arr.max()) < high),
                  f"{name} out of range")

    def ascending(self, arr: np.ndarray, name: str, strict: bool = False) -> None:
        """arr is sorted (NaN fails)."""
        step = arr[1:] > arr[:-1] if strict else arr[1:] >= arr[:-1]
        self.that(bool(np.all(step)), f"{name} not in ascending order")


def scalar(check: Checker, arr: np.ndarray, name: str) -> int:
    """A whole-number 0-d array as an int."""
    check.that(isinstance(arr, np.ndarray) and arr.shape == () and arr.dtype.kind in "iu",
               f"{name} must be a whole number")
    return int(arr)


def check_level(check: Checker, a: dict, k: int, n_points: int, n_lower: int) -> int:
    """Level k: int32 rows ascending within and in range, float64 intervals sorted by enter
    (weighted vertices excepted: they keep the points' order) with enter <= regular <=
    interior, face ids in range. Returns its number of simplices."""
    simplices = check.array(a[f"simplices_{k}"], f"simplices_{k}", np.int32, (None, k + 1))
    n = len(simplices)
    check.ids(simplices, f"vertex ids of simplices_{k}", 0, n_points)
    if k:
        check.that(bool(np.all(simplices[:, 1:] > simplices[:, :-1])),
                   f"rows of simplices_{k} not ascending")
    enter, regular, interior = (check.array(a[f"{name}_{k}"], f"{name}_{k}", np.float64, (n,))
                                for name in ("enter", "regular", "interior"))
    if k == 0 and "weights" in a:
        check.that(bool(np.isfinite(enter).all()), "enter_0 not finite")
    else:
        check.that(n == 0 or (np.isfinite(enter[0]) and np.isfinite(enter[-1])),
                   f"enter_{k} not finite")
        check.ascending(enter, f"enter_{k}")
    check.that(bool(np.all(enter <= regular)), f"regular_{k} below enter or NaN")
    check.that(bool(np.all(regular <= interior)), f"interior_{k} below regular or NaN")
    if k:
        faces = check.array(a[f"face_ids_{k}"], f"face_ids_{k}", np.int32, (n, k + 1))
        check.ids(faces, f"face_ids_{k}", 0, n_lower)
    return n


def cell_measures(points: np.ndarray, cells: np.ndarray) -> np.ndarray:
    """(c,) float64 unsigned area (2D) or volume (3D) of (c, d+1) cells, as the build computes
    them (edge vectors from the first vertex), in chunks of bounded memory."""
    out = np.empty(len(cells))
    for lo in range(0, len(cells), CHUNK):
        part = cells[lo:lo + CHUNK]
        first = points[part[:, 0]]
        edges = [points[part[:, i]] - first for i in range(1, part.shape[1])]
        if points.shape[1] == 2:
            det = edges[0][:, 0] * edges[1][:, 1] - edges[0][:, 1] * edges[1][:, 0]
        else:
            det = np.einsum("ij,ij->i", edges[0], np.cross(edges[1], edges[2]))
        out[lo:lo + CHUNK] = np.abs(det) / math.factorial(points.shape[1])
    return out


def check_table(check: Checker, a: dict, dim: int) -> None:
    """Points, input index, levels, facet adjacency, measures and the interior order."""
    points = check.array(a["points"], "points", np.float64, (None, dim))
    m = len(points)
    check.that(m > dim and bool(np.isfinite(points).all()), "points not finite")
    weighted = "weights" in a  # weighted tables: -1 marks a hidden input point
    if weighted:
        weights = check.array(a["weights"], "weights", np.float64, (m,))
        check.that(bool(np.isfinite(weights).all()), "weights not finite")
    index = check.array(a["input_index"], "input_index", np.int64, (None,))
    check.ids(index, "input_index", -1 if weighted else 0, m)
    counts = [m]
    for k in range(dim + 1):
        counts.append(check_level(check, a, k, m, counts[-1]))
    n_vertices, n_facets, n_cells = counts[1], counts[dim], counts[dim + 1]
    check.that(n_vertices == m, "simplices_0 must list every point")
    cells = check.array(a["facet_cells"], "facet_cells", np.int32, (n_facets, 2))
    check.ids(cells, "facet_cells", -1, n_cells)
    check.that(bool(np.all((cells[:, 0] >= 0) & (cells[:, 0] != cells[:, 1]))),
               "facet_cells: a facet without a cell")
    check.array(a["facet_flip"], "facet_flip", np.bool_, (n_facets,))
    measure = check.array(a["cell_measure"], "cell_measure", np.float64, (n_cells,))
    check.that(bool(np.all(measure >= 0)), "cell_measure negative or NaN")
    rows = spread(n_cells, MEASURE_SAMPLES)
    expected = cell_measures(points, a[f"simplices_{dim}"][rows])
    slack = MEASURE_RTOL * (expected + (expected.mean() if n_cells else 0.0))  # slivers' rounding
    check.that(bool(np.all(np.abs(measure[rows] - expected) <= slack)),
               "cell_measure does not match the cells")
    order = check.array(a["facet_interior_order"], "facet_interior_order", np.int32,
                        (n_facets,))
    check.ids(order, "facet_interior_order", 0, n_facets)
    check.that(bool(np.all(np.bincount(order, minlength=n_facets) == 1)),
               "facet_interior_order is not a permutation")
    check.ascending(a[f"interior_{dim - 1}"][order], "facet_interior_order")
    ambient = scalar(check, a["ambient_dim"], "ambient_dim")
    check.that(ambient in (dim, 3), "ambient_dim")
    if ambient != dim or "frame_origin" in a:
        check.that(bool(np.isfinite(check.array(a["frame_origin"], "frame_origin",
                                                np.float64, (3,))).all()), "frame_origin")
        check.that(bool(np.isfinite(check.array(a["frame_basis"], "frame_basis", np.float64,
                                                (dim, 3))).all()), "frame_basis")



def check_forests(check: Checker, a: dict, dim: int) -> None:
    """The saved topology: spanning forests of the full complex (connected: exact lengths),
    ascending, made of enter values of the right level; dual edges in range."""
    n_points, n_cells = len(a["points"]), len(a[f"enter_{dim}"])
    for name, level, length in (("topo_vertex_forest", 1, n_points - 1),
                                ("topo_dual_forest", dim - 1, n_cells),
                                ("topo_solid_forest", dim, n_cells - 1)):
        forest = check.array(a[name], name, np.float64, (length,))
        check.ascending(forest, name)
        enter, some = a[f"enter_{level}"], forest[spread(length, SAMPLES)]
        at = np.minimum(np.searchsorted(enter, some), max(len(enter) - 1, 0))
        check.that(len(forest) == 0 or bool(np.all(enter[at] == some)),
                   f"{name} holds values that are not enter values of simplices_{level}")
    edges = check.array(a["topo_dual_edges"], "topo_dual_edges", np.int64, (n_cells, 2))
    check.ids(edges, "topo_dual_edges", 0, n_cells + 1)


def check_signature_arrays(check: Checker, a: dict, dim: int) -> np.ndarray:
    """Dtypes, shapes and ranges of the saved signatures; returns the (s,) alphas."""
    alphas = check.array(a["sig_alphas"], "sig_alphas", np.float64, (None,))
    s = len(alphas)
    first = float(a["enter_0"].min()) if "weights" in a and len(a["enter_0"]) else 0.0
    check.that(s > 0 and alphas[0] == first, "sig_alphas must start at the first vertex")
    check.ascending(alphas, "sig_alphas", strict=True)
    last = max(float(a[f"enter_{k}"][-1]) for k in range(dim + 1) if len(a[f"enter_{k}"]))
    check.that(alphas[-1] == last, "sig_alphas do not end at the largest enter value")
    check.that(bool(np.all(check.array(a["sig_betti"], "sig_betti", np.int32, (s, dim)) >= 0)),
               "negative sig_betti")
    check.that(bool(np.all(check.array(a["sig_solid"], "sig_solid", np.int32, (s,)) >= 0)),
               "negative sig_solid")
    for name in ("sig_measure", "sig_boundary"):
        values = check.array(a[name], name, np.float64, (s,))
        check.that(bool(np.all(np.isfinite(values) & (values >= 0))), f"{name} not finite")
    if "sig_opening_pieces" in a:
        opening = check.array(a["sig_opening_pieces"], "sig_opening_pieces", np.float64, ())
        check.that(bool(np.isfinite(opening)), "sig_opening_pieces not finite")
    return alphas


def check_signatures(check: Checker, a: dict, topology, cumulative: np.ndarray) -> None:
    """Saved signatures agree with the saved topology and the cell measures at SAMPLES spread
    entries (Betti numbers, solid components, volume/area): a mismatch is a damaged file.
    `cumulative` is the (c,) running sum of the cell measures in enter order."""
    alphas = a["sig_alphas"]
    rows = spread(len(alphas), SAMPLES)
    at = alphas[rows]
    check.that(np.array_equal(topology.betti_many(at), a["sig_betti"][rows]),
               "sig_betti disagrees with the topology")
    check.that(np.array_equal(topology.solid_components(at), a["sig_solid"][rows]),
               "sig_solid disagrees with the topology")
    cells_in = np.searchsorted(topology.enter_sorted[topology.dim], at, side="right")
    measure = np.concatenate([[0.0], cumulative])[cells_in]
    check.that(np.allclose(a["sig_measure"][rows], measure, rtol=MEASURE_RTOL, atol=0.0),
               "sig_measure disagrees with the cell measures")

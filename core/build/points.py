"""Input validation, exact-duplicate merging, flatness detection and a cache-friendly
spatial (Morton) order for point sets."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from core.errors import InputError
from core.parallel import argsort_stable, in_chunks
from core.tolerances import FLAT_RTOL, MAX_COORDINATE

#: clearly_spread's least scatter eigenvalue, relative to the largest: FLAT_RTOL squared
#: is 1e-18, so a set this far from flat is decided without an SVD
SPREAD_MARGIN = 1e-6
CODE_CHUNK = 1 << 16  # points per chunk of Morton codes


def first_too_large(points: np.ndarray) -> tuple[int, float] | None:
    """(row, value) of the first finite coordinate beyond MAX_COORDINATE for the points'
    dimension (squared distances and areas or volumes would overflow float64), or None."""
    limit = MAX_COORDINATE[points.shape[1]]
    with np.errstate(invalid="ignore"):
        big = np.isfinite(points) & (np.abs(points) > limit)
    rows = np.flatnonzero(big.any(axis=1))
    if len(rows) == 0:
        return None
    row = int(rows[0])
    return row, float(points[row][big[row]][0])


def too_large_message(points: np.ndarray, row: int, value: float) -> str:
    """Why a coordinate is refused, in words."""
    d = points.shape[1]
    return (f"coordinate {value:.3g} (point {row + 1}) is too large: beyond "
            f"{MAX_COORDINATE[d]:.0e} the {'areas' if d == 2 else 'volumes'} of a {d}D alpha "
            "shape overflow float64 (a corrupt value, or rescale the points)")


def as_points(points: object) -> np.ndarray:
    """(n, d) float64 copy of `points`, d in {2, 3}; InputError for anything else."""
    try:
        arr = np.array(points, dtype=np.float64)
    except (TypeError, ValueError) as exc:
        raise InputError(f"points must be numbers: {exc}") from None
    if arr.ndim != 2 or arr.shape[1] not in (2, 3):
        raise InputError(f"points must be an (n, 2) or (n, 3) array, got shape {arr.shape}")
    if arr.shape[0] == 0:
        raise InputError("no points: the input is empty")
    extreme = first_too_large(arr)
    if extreme is not None:
        raise InputError(too_large_message(arr, *extreme))
    bad = ~np.isfinite(arr).all(axis=1)
    if bad.any():
        first = int(np.flatnonzero(bad)[0])
        raise InputError(
            f"{int(bad.sum())} point(s) have NaN or infinite coordinates (first: row {first}); "
            "drop or fix them first"
        )
    return arr


def merge_duplicates(points: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Unique rows in order of first appearance, and (n,) int64 row of each input point.

    Hashes rows first so that duplicate-free input costs one sort of n integers.
    """
    n = points.shape[0]
    bits = np.ascontiguousarray(points + 0.0).view(np.uint64)  # + 0.0 folds -0.0 into 0.0
    mix = np.array([0x9E3779B97F4A7C15, 0xC2B2AE3D27D4EB4F, 0x165667B19E3779F9], np.uint64)
    h = (bits * mix[: points.shape[1]]).sum(axis=1, dtype=np.uint64)
    hs = np.sort(h)
    if not (hs[1:] == hs[:-1]).any():
        return points, np.arange(n, dtype=np.int64)
    clash = np.isin(h, hs[1:][hs[1:] == hs[:-1]])
    cand = np.flatnonzero(clash)
    order = cand[np.lexsort(points[cand].T[::-1])]
    same = (points[order[1:]] == points[order[:-1]]).all(axis=1)
    group = np.concatenate(([0], np.cumsum(~same)))
    first = np.minimum.reduceat(order, np.flatnonzero(np.concatenate(([True], ~same))))
    rep = first[group]
    target = np.arange(n, dtype=np.int64)
    target[order] = rep
    keep = target == np.arange(n)
    new_id = np.cumsum(keep) - 1
    return points[keep], new_id[target]


@dataclass(frozen=True)
class Frame:
    """Affine frame of planar 3D input: ambient = origin + local @ basis."""

    origin: np.ndarray  # (3,) float64
    basis: np.ndarray  # (2, 3) float64, orthonormal rows


def flatness(points: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Centroid, singular values (descending) and right singular vectors of the points."""
    centroid = points.mean(axis=0)
    centred = points - centroid
    scale = np.abs(centred).max()
    if scale == 0.0:
        return centroid, np.zeros(points.shape[1]), np.eye(points.shape[1])
    _, s, vt = np.linalg.svd(centred / scale, full_matrices=False)
    return centroid, s * scale, vt


def clearly_spread(points: np.ndarray) -> bool:
    """True when the (n, d) points certainly spread in every direction, far from flat: the
    least eigenvalue of their scaled scatter matrix (one BLAS pass, not an SVD) is above a
    margin that dwarfs both its rounding error (about n * eps of the largest) and the flat
    threshold (FLAT_RTOL of the largest singular value, squared). False says nothing: the
    SVD (flatness) decides then."""
    n = len(points)
    if n < 2:
        return False
    centred = points - points.mean(axis=0)
    scale = np.abs(centred).max()
    if not np.isfinite(scale) or scale == 0.0:
        return False
    centred /= scale
    eigen = np.linalg.eigvalsh(centred.T @ centred)
    margin = max(SPREAD_MARGIN, 1000.0 * n * np.finfo(np.float64).eps)
    return bool(eigen[0] > margin * eigen[-1])


def check_spread(points: np.ndarray) -> Frame | None:
    """Frame to build a planar 3D set in 2D, or None; InputError if too few or collinear."""
    n, d = points.shape
    if n < d + 1 and not (d == 3 and n == 3):
        raise InputError(
            f"only {n} distinct point(s): a {d}D alpha shape needs at least {d + 1} points "
            "that are not all on one line" + (" or plane" if d == 3 else "")
        )
    if clearly_spread(points):  # neither one point, nor a line, nor a plane
        return None
    centroid, s, vt = flatness(points)
    if s[0] == 0.0:
        raise InputError("all points are the same point")
    if s[1] <= FLAT_RTOL * s[0]:
        raise InputError("the points all lie on one line: an alpha shape needs 2D or 3D spread")
    if d == 3 and s[2] <= FLAT_RTOL * s[0]:
        return Frame(origin=centroid, basis=vt[:2].copy())
    return None


def _spread_bits(x: np.ndarray, dim: int) -> np.ndarray:
    """Insert dim-1 zero bits between the low bits of x (uint64), for Morton codes."""
    if dim == 2:
        masks = ((16, 0x0000FFFF0000FFFF), (8, 0x00FF00FF00FF00FF), (4, 0x0F0F0F0F0F0F0F0F),
                 (2, 0x3333333333333333), (1, 0x5555555555555555))
        x = x & np.uint64(0xFFFFFFFF)
    else:
        masks = ((32, 0x001F00000000FFFF), (16, 0x001F0000FF0000FF), (8, 0x100F00F00F00F00F),
                 (4, 0x10C30C30C30C30C3), (2, 0x1249249249249249))
        x = x & np.uint64(0x1FFFFF)
    for shift, mask in masks:
        x = (x | (x << np.uint64(shift))) & np.uint64(mask)
    return x


def spatial_order(points: np.ndarray) -> np.ndarray:
    """(m,) permutation putting the points in Morton (Z-curve) order.

    Neighbours in space become neighbours in memory: Qhull and every gather over simplices
    then hit the cache far more often (20% faster triangulation on scans in random order).
    """
    dim = points.shape[1]
    bits = 32 if dim == 2 else 21
    low = points.min(axis=0)
    extent = float((points.max(axis=0) - low).max()) or 1.0
    factor = (2**bits - 1) / extent
    code = np.empty(len(points), dtype=np.uint64)

    def part(start: int, stop: int) -> None:  # element by element: chunks change nothing
        if np.isfinite(factor):
            grid = ((points[start:stop] - low) * factor).astype(np.uint64)
        else:  # a subnormal extent (coordinates near 1e-310): 1 / extent overflows
            grid = ((points[start:stop] - low) / extent * (2**bits - 1)).astype(np.uint64)
        mine = code[start:stop]
        mine[:] = 0
        for axis in range(dim):
            mine |= _spread_bits(grid[:, axis], dim) << np.uint64(axis)

    in_chunks(part, len(points), CODE_CHUNK)  # the codes' temporaries stay in cache
    return argsort_stable(code)


def orderable_bits(points: np.ndarray) -> np.ndarray:
    """(m, d) uint64 keys ordered as the coordinates are (-0.0 taken as 0.0): the float bits
    with the sign bit flipped for positive values and every bit flipped for negative ones."""
    bits = (np.ascontiguousarray(points, dtype=np.float64) + 0.0).view(np.uint64)
    negative = (bits >> np.uint64(63)).astype(bool)
    return np.where(negative, ~bits, bits | np.uint64(1 << 63))


def canonical_order(points: np.ndarray) -> np.ndarray:
    """(m,) permutation putting the points in Morton (Z-curve) order of their coordinates'
    bits (orderable_bits): the numbering of the points the interval table is built on.

    The order of two points depends on those two points alone (every bit is interleaved,
    from the highest one any two points of the set differ in), so any subset of a set is
    numbered in the same relative order as the set: a simplex's vertices come in the same
    order in a tile (core.tiled) as in the whole set, so its radii round alike. Locality is
    that of spatial_order, which orders Qhull's input (its grid follows the set's box).
    """
    m, dim = points.shape
    if m < 2:
        return np.arange(m)
    keys = orderable_bits(points)
    differing = np.bitwise_or.reduce(keys ^ keys[0], axis=0)
    top = max(int(x).bit_length() for x in differing.tolist())
    if top == 0:  # every point the same
        return np.arange(m)
    width = 32 if dim == 2 else 21
    windows = [(max(high - width, 0), high) for high in range(top, 0, -width)]
    order = argsort_stable(_morton_word(keys, *windows[0]))
    if len(windows) == 1:
        return order
    first = _morton_word(keys[order], *windows[0])
    tied = np.r_[False, first[1:] == first[:-1]]
    tied[:-1] |= tied[1:]  # both ends of every run of equal words
    if not tied.any():
        return order
    rows = np.flatnonzero(tied)  # positions in `order`; runs stay in place, sorted inside
    later = [_morton_word(keys[order[rows]], lo, hi) for lo, hi in windows[1:]]
    order[rows] = order[rows[np.lexsort([*later[::-1], first[rows]])]]
    return order


def _morton_word(keys: np.ndarray, low: int, high: int) -> np.ndarray:
    """(m,) uint64 Morton code of the bits low..high-1 of (m, d) `keys`, interleaved with
    the last axis highest (spatial_order)."""
    m, dim = keys.shape
    shift, mask = np.uint64(low), np.uint64((1 << (high - low)) - 1)
    code = np.empty(m, dtype=np.uint64)

    def part(start: int, stop: int) -> None:  # element by element: chunks change nothing
        mine = code[start:stop]
        mine[:] = 0
        for axis in range(dim):
            mine |= _spread_bits((keys[start:stop, axis] >> shift) & mask, dim) << np.uint64(axis)

    in_chunks(part, m, CODE_CHUNK)  # the codes' temporaries stay in cache
    return code

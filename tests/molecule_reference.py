"""Independent references for molecules: gudhi's weighted alpha complex, freesasa's
Lee–Richards area, Monte Carlo volume and a voxel flood-fill of the empty space."""

from __future__ import annotations

import numpy as np
from scipy import ndimage
from scipy.spatial import cKDTree

from tests.reference import data_dir


def shared_molecule(name: str):
    """Path of a shared molecule file, or None when the data folder is missing."""
    root = data_dir()
    return None if root is None else root / name


def gudhi_dual(centres: np.ndarray, radii: np.ndarray) -> dict:
    """gudhi's weighted regular triangulation: {k: (simplices (n, k+1), enter (n,) alpha²)}."""
    import gudhi

    st = gudhi.AlphaComplex(points=centres, weights=radii ** 2).create_simplex_tree()
    out: dict[int, tuple[list, list]] = {k: ([], []) for k in range(4)}
    for simplex, value in st.get_simplices():
        out[len(simplex) - 1][0].append(sorted(simplex))
        out[len(simplex) - 1][1].append(value)
    return {k: (np.array(s, np.int64).reshape(-1, k + 1), np.array(f))
            for k, (s, f) in out.items()}


def gudhi_betti2(centres: np.ndarray, radii: np.ndarray, alpha2: float = 0.0) -> int:
    """b2 of gudhi's weighted alpha complex at alpha²."""
    import gudhi

    st = gudhi.AlphaComplex(points=centres, weights=radii ** 2).create_simplex_tree(
        max_alpha_square=alpha2)
    st.compute_persistence(persistence_dim_max=True)
    return st.persistent_betti_numbers(alpha2, alpha2)[2]


def dual_at_zero(table: dict) -> dict:
    """{k: simplices of the dual complex (alpha² <= 0)}."""
    return {k: s[f <= 0] for k, (s, f) in table.items()}


def facet_cells(triangles: np.ndarray, tets: np.ndarray) -> np.ndarray:
    """(n_tri, 2) the tetrahedra on both sides of each triangle (-1 = beyond the hull)."""
    base = int(max(triangles.max(), tets.max())) + 1

    def key(rows):
        return (rows[:, 0] * base + rows[:, 1]) * base + rows[:, 2]

    faces = np.concatenate([np.sort(np.delete(tets, j, axis=1), axis=1) for j in range(4)])
    owner = np.tile(np.arange(len(tets)), 4)
    order = np.argsort(key(triangles))
    pos = order[np.searchsorted(key(triangles)[order], key(faces))]
    by = np.argsort(pos, kind="stable")
    pos, owner = pos[by], owner[by]
    second = np.r_[False, pos[1:] == pos[:-1]]
    out = np.full((len(triangles), 2), -1, np.int64)
    out[pos[~second], 0] = owner[~second]
    out[pos[second], 1] = owner[second]
    return out


def freesasa_area(centres: np.ndarray, radii: np.ndarray, slices: int = 200,
                  probe: float = 0.0) -> tuple[float, np.ndarray]:
    """freesasa's Lee–Richards total and per-atom areas of balls radii + probe."""
    import freesasa

    params = freesasa.Parameters({"algorithm": freesasa.LeeRichards, "n-slices": slices,
                                  "probe-radius": probe})
    result = freesasa.calcCoord(np.asarray(centres, float).ravel(), list(map(float, radii)),
                                params)
    return result.totalArea(), np.array([result.atomArea(i) for i in range(len(radii))])


def monte_carlo_volume(centres, radii, rng, n=2_000_000) -> tuple[float, float]:
    """(volume, standard error) of the union of balls by uniform sampling of its box."""
    from scipy.spatial import cKDTree

    lo, hi = (centres - radii[:, None]).min(0), (centres + radii[:, None]).max(0)
    x = rng.uniform(lo, hi, size=(n, 3))
    pairs = cKDTree(x).sparse_distance_matrix(cKDTree(centres), radii.max(),
                                              output_type="ndarray")
    inside = np.zeros(n, bool)
    inside[pairs["i"][pairs["v"] <= radii[pairs["j"]]]] = True
    box, p = float(np.prod(hi - lo)), inside.mean()
    return p * box, box * np.sqrt(p * (1 - p) / n)


def flood_fill_voids(centres, radii, step: float) -> np.ndarray:
    """Volumes of the enclosed empty regions of a voxel grid (voxel centres in no ball)."""
    from scipy.spatial import cKDTree

    lo, hi = (centres - radii[:, None]).min(0) - 2 * step, (centres + radii[:, None]).max(0)
    axes = [np.arange(lo[i], hi[i] + 2 * step, step) for i in range(3)]
    x = np.stack(np.meshgrid(*axes, indexing="ij"), -1).reshape(-1, 3)
    pairs = cKDTree(x).sparse_distance_matrix(cKDTree(centres), radii.max(),
                                              output_type="ndarray")
    full = np.zeros(len(x), bool)
    full[pairs["i"][pairs["v"] <= radii[pairs["j"]]]] = True
    free = ~full.reshape([len(a) for a in axes])
    labels, n = ndimage.label(free)  # 6-connectivity: thin gaps do not join regions
    outside = labels[0, 0, 0]
    sizes = np.bincount(labels.ravel(), minlength=n + 1)
    return np.array([sizes[i] * step ** 3 for i in range(1, n + 1) if i != outside])


def shell(centre, radius: float, n: int, ball: float) -> tuple[np.ndarray, np.ndarray]:
    """n balls of one radius evenly spread (Fibonacci) on a sphere: a hollow shell."""
    i = np.arange(n) + 0.5
    phi, theta = np.arccos(1 - 2 * i / n), np.pi * (1 + 5 ** 0.5) * i
    pts = np.stack([np.cos(theta) * np.sin(phi), np.sin(theta) * np.sin(phi), np.cos(phi)], 1)
    return np.asarray(centre) + radius * pts, np.full(n, ball)


def tet_volumes(corners: np.ndarray) -> np.ndarray:
    """(t,) volumes of the tetrahedra (t, 4, 3)."""
    e = corners[:, 1:] - corners[:, :1]
    return np.abs(np.linalg.det(e)) / 6.0


def uniform_in_tets(corners: np.ndarray, n: int, rng) -> tuple[np.ndarray, np.ndarray]:
    """(n, 3) points uniform in the union of tetrahedra (t, 4, 3), and the cell of each."""
    vol = tet_volumes(corners)
    cell = rng.choice(len(corners), size=n, p=vol / vol.sum())
    lam = np.diff(np.sort(rng.random((n, 3)), 1), prepend=0.0, append=1.0, axis=1)
    return np.einsum("pi,pij->pj", lam, corners[cell]), cell


def free_in_tets(corners, centres, radii, n: int, rng, chunk: int = 1_000_000
                 ) -> tuple[float, float]:
    """(volume, standard error) of the part of the tetrahedra (t, 4, 3) in no ball: n
    uniform samples of them, chunked. The ball of least power decides a sample: it is the
    nearest centre lifted to (c, sqrt(R² - r²)) in 4D (R the largest radius), the sample
    taken as (x, 0), since |x - c|² + R² - r² is its power plus R²."""
    vol = tet_volumes(corners)
    tree, reach = lifted_centres(centres, radii)
    free = 0
    for start in range(0, n, chunk):
        x, _ = uniform_in_tets(corners, min(chunk, n - start), rng)
        dist, _ = tree.query(np.column_stack([x, np.zeros(len(x))]))
        free += int((dist > reach).sum())
    p = free / n
    return p * vol.sum(), vol.sum() * np.sqrt(p * (1 - p) / n)


def lifted_centres(centres: np.ndarray, radii: np.ndarray) -> tuple[cKDTree, float]:
    """A tree of the centres lifted to (c, sqrt(R² - r²)) and R, the largest radius: a point
    (x, 0) lies in a ball exactly when a lifted centre is nearer than R (free_in_tets)."""
    reach = float(radii.max())
    return cKDTree(np.column_stack([centres, np.sqrt(reach ** 2 - radii ** 2)])), reach


def exposed_points(points: np.ndarray, ball: np.ndarray, centres: np.ndarray,
                   radii: np.ndarray) -> np.ndarray:
    """(p,) bool: which points on the spheres of `ball` lie in no other ball. Every ball is
    asked (its own has power about 0 there, a covering one less: one of the two nearest)."""
    tree, reach = lifted_centres(centres, radii)
    dist, idx = tree.query(np.column_stack([points, np.zeros(len(points))]), k=2,
                           distance_upper_bound=reach)
    return ~((idx != ball[:, None]) & (dist < reach)).any(1)

"""The measurements of bench_core.py; each runs in its own process (isolate.run_isolated)."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np
from datasets import read_points
from isolate import Probe, StageClock, best_of

QUANTILES = (0.0, 0.1, 0.5, 0.9, 1.0)


def _tiny() -> np.ndarray:
    """(50, 3) float64 points for a warm-up call, so lazy imports are not timed or measured."""
    return np.random.default_rng(0).random((50, 3))


def _warm_up_queries(ac: object) -> None:
    """Run every timed query once on a tiny complex (imports the modules they load lazily)."""
    _materialize(ac.shape(float(np.median(ac.spectrum()))), ac.dim)
    for name in ("signatures", "optimal_alpha"):
        if hasattr(ac, name):
            getattr(ac, name)()


def scipy_delaunay(points_path: str) -> dict:
    """scipy.spatial.Delaunay(points) alone: time and peak memory."""
    from scipy.spatial import Delaunay

    Delaunay(_tiny())
    points = read_points(points_path)
    probe = Probe()
    tri = Delaunay(points)
    return probe.result(cells=int(tri.simplices.shape[0]))


def gudhi_alpha(points_path: str) -> dict:
    """gudhi.AlphaComplex(points, precision='fast').create_simplex_tree(): time and peak."""
    import gudhi

    gudhi.AlphaComplex(points=_tiny(), precision="fast").create_simplex_tree()
    points = read_points(points_path)
    probe = Probe()
    tree = gudhi.AlphaComplex(points=points, precision="fast").create_simplex_tree()
    return probe.result(simplices=int(tree.num_simplices()))


def core_build(points_path: str, table_path: str) -> dict:
    """AlphaComplex.from_points(points): time and peak; then ac.save(table_path) timed once."""
    from core import AlphaComplex

    AlphaComplex.from_points(_tiny())
    points = read_points(points_path)
    clock = StageClock()
    probe = Probe()
    ac = AlphaComplex.from_points(points, progress=clock)
    result = probe.result(dim=int(ac.dim), counts=[int(ac.simplices(k).shape[0]) for k in
                                                   range(ac.dim + 1)])
    result["stages"] = clock.stages()
    result["save_seconds"], result["save_cpu_seconds"], _ = best_of(
        lambda: ac.save(table_path), 1)
    return result


def core_query(table_path: str, reps: int) -> dict:
    """AlphaComplex.load (best of reps), signatures(), shape(alpha) at spectrum quantiles."""
    from core import AlphaComplex

    _warm_up_queries(AlphaComplex.from_points(_tiny()))
    result: dict = {}
    ac = _timed(result, "load", lambda: AlphaComplex.load(table_path), reps)
    if hasattr(ac, "signatures"):  # first, on a table no other query has warmed up
        _timed(result, "signatures", ac.signatures)
        ac = AlphaComplex.load(table_path)
    spectrum = np.asarray(_timed(result, "spectrum_first_call", ac.spectrum))
    middle = float(spectrum[len(spectrum) // 2])
    _timed(result, "shape_first_call", lambda: _materialize(ac.shape(middle), ac.dim))
    shapes = [_time_shapes(ac, spectrum, q, reps) for q in QUANTILES]
    if hasattr(ac, "optimal_alpha"):
        result["optimal_alpha"] = float(_timed(result, "optimal_alpha", ac.optimal_alpha))
        shapes.append(_time_shapes(ac, spectrum, None, reps, result["optimal_alpha"]))
    worst = max(shapes, key=lambda shape: shape["seconds"])["alpha"]
    result.update(spectrum_size=len(spectrum), shapes=shapes,
                  shape_parts=_shape_parts(ac, worst, reps))
    return result


def _shape_parts(ac: object, alpha: float, reps: int) -> list[dict]:
    """Best time of each AlphaShape attribute, touched in _materialize's order, at one alpha."""
    parts = [("cells", lambda s: s.cells), ("boundary_facets", lambda s: s.boundary_facets),
             ("regular_facets", lambda s: s.regular_facets)]
    parts += [(f"singular({k})", lambda s, k=k: s.singular(k)) for k in range(ac.dim)]
    parts.append(("measure", lambda s: s.measure))
    best = {name: (float("inf"), float("inf")) for name, _ in parts}
    for _ in range(reps):
        shape = ac.shape(alpha)
        for name, touch in parts:
            wall, cpu, _ = best_of(lambda t=touch, s=shape: t(s), 1)
            best[name] = (min(best[name][0], wall), min(best[name][1], cpu))
    return [{"part": name, "alpha": alpha, "seconds": wall, "cpu_seconds": cpu}
            for name, (wall, cpu) in best.items()]


def _timed(result: dict, name: str, fn: Callable[[], Any], reps: int = 1) -> Any:
    """fn() timed as best of reps; stores name_seconds and name_cpu_seconds in result."""
    wall, cpu, value = best_of(fn, reps)
    result[f"{name}_seconds"], result[f"{name}_cpu_seconds"] = wall, cpu
    return value


def _time_shapes(ac: object, spectrum: np.ndarray, q: float | None, reps: int,
                 alpha: float | None = None) -> dict:
    """Best time of reps fully materialized shapes at distinct neighbouring critical alphas.

    Distinct alphas keep any per-alpha cache in the core from turning repeats into lookups.
    """
    if alpha is not None:
        start = int(np.searchsorted(spectrum, alpha))
    else:
        start = round(q * (len(spectrum) - 1))
    start = int(np.clip(start, 0, max(0, len(spectrum) - reps)))
    alphas = spectrum[start:start + reps] if len(spectrum) else np.zeros(1)
    runs = [best_of(lambda a=float(a): _materialize(ac.shape(a), ac.dim), 1) for a in alphas]
    best = int(np.argmin([run[0] for run in runs]))
    wall, cpu, size = runs[best]
    return {"quantile": q, "alpha": float(alphas[best]), "seconds": wall,
            "cpu_seconds": cpu, "simplices": size}


def _materialize(shape: object, dim: int) -> int:
    """Touch every array of an AlphaShape; returns how many simplices it holds in all."""
    arrays = [shape.cells, shape.boundary_facets, shape.regular_facets]
    arrays += [shape.singular(k) for k in range(dim)]
    _ = shape.measure
    return int(sum(np.asarray(a).shape[0] for a in arrays))


def open3d_alpha(points_path: str, alphas: list[float]) -> dict:
    """Open3D: TetraMesh once, then create_from_point_cloud_alpha_shape at each alpha (radius)."""
    import open3d as o3d

    o3d.geometry.TetraMesh.create_from_point_cloud(
        o3d.geometry.PointCloud(o3d.utility.Vector3dVector(_tiny())))
    points = read_points(points_path)
    pcd = o3d.geometry.PointCloud(o3d.utility.Vector3dVector(points))
    probe = Probe()
    tetra, pt_map = o3d.geometry.TetraMesh.create_from_point_cloud(pcd)
    result = probe.result(version=o3d.__version__)
    create = o3d.geometry.TriangleMesh.create_from_point_cloud_alpha_shape
    per_alpha = []
    for alpha in alphas:
        wall, cpu, mesh = best_of(lambda a=alpha: create(pcd, a, tetra, pt_map), 1)
        per_alpha.append({"alpha": alpha, "seconds": wall, "cpu_seconds": cpu,
                          "triangles": len(mesh.triangles)})
    result["per_alpha"] = per_alpha
    return result

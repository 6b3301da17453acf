"""Saving and loading interval tables as .npz (no pickles), with atomic writes.

Layout (format "alphascoop-table", version 1): `points` (m, dim) float64, `input_index` (n,)
int64, `dim`, `ambient_dim`, optional `frame_origin` (3,) / `frame_basis` (2, 3); for each
k in 0..dim: `simplices_k` (n_k, k+1) int32 sorted by enter, `enter_k`/`regular_k`/`interior_k`
(n_k,) float64 radii (inf = never), `face_ids_k` (n_k, k+1) int32 for k >= 1; `facet_cells`
(f, 2) int32 (-1 = outside), `facet_flip` (f,) bool, `cell_measure` (c,) float64,
`facet_interior_order` (f,) int32 (facet rows by ascending interior).

Weighted tables (tables without it are classic, so older files load unchanged) add `weights`
(m,) float64 squared radii aligned with `points`; their values are signed radii and
`input_index` holds -1 for hidden points.

Optional, written once computed, so re-opening skips the topology pass: `sig_alphas` (s,)
float64 (the spectrum), `sig_betti` (s, dim) int32, `sig_solid` (s,) int32, `sig_measure`,
`sig_boundary` (s,) float64; `topo_vertex_forest`, `topo_dual_forest` (float64),
`topo_dual_edges` (fd, 2) int64, `topo_solid_forest` (float64).

Optional, for a table built in a mode (core/modes.py; absent = classic): `mode_density` (int,
0 = off), `mode_combine` (str), `mode_anisotropy` (float), `mode_normals` (str).
"""

from __future__ import annotations

import os
import zipfile
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from .atomic import atomic_write
from .errors import FileFormatError, InputError
from .modes import Mode, make_mode
from .points import Frame
from .table import Level, Table

if TYPE_CHECKING:
    from .complex import AlphaComplex

FORMAT, VERSION = "alphascoop-table", 1


def _arrays(ac: AlphaComplex) -> dict[str, np.ndarray]:
    table = ac._table
    out = {"format": np.array(FORMAT), "version": np.array(VERSION), "dim": np.array(ac.dim),
           "ambient_dim": np.array(ac.ambient_dim), "points": ac.points,
           "input_index": ac.input_index, "facet_cells": table.facet_cells,
           "facet_flip": table.facet_flip, "cell_measure": table.cell_measure,
           "facet_interior_order": table.facet_interior_order}
    if ac.frame is not None:
        out["frame_origin"], out["frame_basis"] = ac.frame.origin, ac.frame.basis
    if ac.weights is not None:
        out["weights"] = ac.weights
    if ac.mode.active:
        out.update(mode_density=np.array(ac.mode.density or 0),
                   mode_combine=np.array(ac.mode.combine),
                   mode_anisotropy=np.array(ac.mode.anisotropy),
                   mode_normals=np.array(ac.mode.normals))
    out.update(_derived_arrays(ac))
    for k, level in enumerate(table.levels):
        out[f"simplices_{k}"] = level.simplices
        out[f"enter_{k}"], out[f"regular_{k}"] = level.enter, level.regular
        out[f"interior_{k}"] = level.interior
        if level.face_ids is not None:
            out[f"face_ids_{k}"] = level.face_ids
    return out


def _derived_arrays(ac: AlphaComplex) -> dict[str, np.ndarray]:
    """Signatures and topology forests, if `ac` has computed them (never computed here)."""
    if "_signatures" not in ac.__dict__:
        return {}
    sig, topo = ac.signatures(), ac._topology
    return {"sig_alphas": sig.alphas, "sig_betti": sig.betti, "sig_solid": sig.solid_components,
            "sig_measure": sig.measure, "sig_boundary": sig.boundary_measure,
            "topo_vertex_forest": topo.vertex_forest, "topo_dual_forest": topo.dual_forest,
            "topo_dual_edges": topo.dual_edges, "topo_solid_forest": topo.solid_forest}


def _adopt_derived(ac: AlphaComplex, a: dict[str, np.ndarray], path: Path) -> None:
    """Hand saved signatures and topology to `ac` after checking their shapes."""
    from .signatures import Signatures
    from .topology import Topology, ascending

    alphas = a["sig_alphas"]
    s, dim = len(alphas), ac.dim
    first = 0.0 if ac.weights is None else float(ac._table.levels[0].enter.min())
    _check(alphas.ndim == 1 and s > 0 and alphas[0] == first
           and bool(np.all(alphas[1:] > alphas[:-1])), path, "sig_alphas")
    for name, shape in (("sig_betti", (s, dim)), ("sig_solid", (s,)), ("sig_measure", (s,)),
                        ("sig_boundary", (s,))):
        _check(a[name].shape == shape, path, name)
    edges = a["topo_dual_edges"]
    _check(edges.shape == (len(a["topo_dual_forest"]), 2), path, "topo_dual_edges")
    levels = ac._table.levels
    topology = Topology(dim=dim, n_cells=len(levels[dim].enter),
                        enter_sorted=tuple(ascending(level.enter) for level in levels),
                        vertex_forest=a["topo_vertex_forest"], dual_forest=a["topo_dual_forest"],
                        dual_edges=edges, solid_forest=a["topo_solid_forest"])
    signatures = Signatures(dim=dim, alphas=alphas, betti=a["sig_betti"],
                            solid_components=a["sig_solid"], measure=a["sig_measure"],
                            boundary_measure=a["sig_boundary"],
                            intervals=tuple(ac.intervals(k) for k in range(dim + 1)))
    for arr in (*topology.__dict__.values(), *signatures.__dict__.values()):
        if isinstance(arr, np.ndarray):
            arr.flags.writeable = False
    ac._adopt(topology, signatures)


def _mode(a: dict[str, np.ndarray], path: Path) -> Mode:
    """The mode saved with a table (classic when none was)."""
    if "mode_density" not in a:
        return Mode()
    try:
        density = int(a["mode_density"])
        return make_mode(density or None, str(a["mode_combine"]), float(a["mode_anisotropy"]),
                         str(a["mode_normals"]) == "given")
    except (InputError, TypeError, ValueError):
        raise FileFormatError(f"{path}: not a valid Alpha Scoop table (mode)") from None


def save(ac: AlphaComplex, path: str | os.PathLike) -> None:
    """Write `ac` to `path` (.npz) atomically."""
    atomic_write(path, lambda handle: np.savez(handle, **_arrays(ac)))


def _check(condition: bool, path: Path, what: str) -> None:
    if not condition:
        raise FileFormatError(f"{path}: not a valid Alpha Scoop table ({what})")


def _read(path: Path) -> dict[str, np.ndarray]:
    try:  # our own handle: np.load leaks the one it opens when the zip is broken
        with open(path, "rb") as fh:
            data = np.load(fh, allow_pickle=False)
            if not isinstance(data, np.lib.npyio.NpzFile):
                raise ValueError("a single array, not an archive")
            with data:
                arrays = {name: data[name] for name in data.files}
    except FileNotFoundError:
        raise FileFormatError(f"{path}: no such file") from None
    except (OSError, ValueError, EOFError, zipfile.BadZipFile, KeyError) as exc:
        raise FileFormatError(f"{path}: not a readable .npz table ({exc})") from None
    _check(str(arrays.get("format", "")) == FORMAT, path, "missing format tag")
    _check(int(arrays.get("version", -1)) == VERSION, path, "unknown version")
    return arrays


def load(cls: type[AlphaComplex], path: str | os.PathLike) -> AlphaComplex:
    """Read a table written by `save`, checking shapes so a damaged file fails clearly."""
    path = Path(path)
    a = _read(path)
    try:
        dim = int(a["dim"])
        _check(dim in (2, 3), path, "dimension")
        levels = []
        for k in range(dim + 1):
            simplices = a[f"simplices_{k}"]
            n = len(simplices)
            _check(simplices.ndim == 2 and simplices.shape[1] == k + 1, path, f"simplices_{k}")
            level = Level(simplices, a[f"enter_{k}"], a[f"regular_{k}"], a[f"interior_{k}"],
                          a.get(f"face_ids_{k}"))
            for arr in (level.enter, level.regular, level.interior):
                _check(arr.shape == (n,) and arr.dtype == np.float64, path, f"intervals_{k}")
                _check(not np.isnan(arr).any(), path, f"NaN in intervals_{k}")
            _check(k == 0 or (level.face_ids is not None and level.face_ids.shape == (n, k + 1)),
                   path, f"face_ids_{k}")
            levels.append(level)
        points = a["points"]
        _check(points.ndim == 2 and points.shape[1] == dim, path, "points")
        for k, level in enumerate(levels):
            s = level.simplices
            _check(s.size == 0 or (s.min() >= 0 and s.max() < len(points)), path,
                   f"vertex ids of simplices_{k} out of range")
        _check(a["facet_cells"].shape == (len(levels[dim - 1].enter), 2), path, "facet_cells")
        _check(a["cell_measure"].shape == (len(levels[dim].enter),), path, "cell_measure")
        frame = (Frame(a["frame_origin"], a["frame_basis"]) if "frame_origin" in a else None)
        order = a["facet_interior_order"]
        n_facets = len(levels[dim - 1].enter)
        _check(order.shape == (n_facets,) and (n_facets == 0 or (order.min() >= 0
               and order.max() < n_facets)), path, "facet_interior_order")
        table = Table(levels, a["facet_cells"], a["facet_flip"], a["cell_measure"], order)
        weights = a.get("weights")
        _check(weights is None or (weights.shape == (len(points),)
                                   and weights.dtype == np.float64), path, "weights")
        ac = cls(points, a["input_index"], table, frame, int(a["ambient_dim"]), _mode(a, path),
                 weights)
        if "sig_alphas" in a:
            _adopt_derived(ac, a, path)
        return ac
    except KeyError as exc:
        raise FileFormatError(f"{path}: not a valid Alpha Scoop table (missing {exc})") from None

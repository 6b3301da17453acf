"""The topology of a complex as a small .npz (no pickles): how the topology process hands its
results to the window, which attaches them to its own complex without copying the table.

Arrays: the signatures `sig_betti` (s, dim) int32, `sig_solid` (s,) int32, `sig_measure`,
`sig_boundary` (s,) float64, `sig_opening` (); the forests `topo_vertex_forest`,
`topo_dual_forest`, `topo_solid_forest` float64 and `topo_dual_edges` (fd, 2) int64; the
persistence pairs `pers_components`, `pers_cavities` (n, 2) float64; `optimal_alpha` and
`default_alpha` (); `entry_saved` () bool (the cache entry was rewritten with them).
"""

from __future__ import annotations

import os
from dataclasses import dataclass

import numpy as np

from core.arrays import readonly
from core.atomic import atomic_write
from core.complex import AlphaComplex
from core.errors import FileFormatError
from core.persistence import Persistence
from core.signatures import Signatures
from core.topology import Topology, ascending


@dataclass(frozen=True, eq=False)
class TopologyParts:
    """What the topology pass found for one complex, ready to attach (`attach`)."""

    topology: Topology
    signatures: Signatures
    persistence: Persistence
    optimal_alpha: float
    default_alpha: float
    entry_saved: bool


def write_topology(path: str | os.PathLike, ac: AlphaComplex, entry_saved: bool) -> None:
    """Write ac's topology, signatures, persistence and optimal/default alpha (computed here
    if they are not yet) to path atomically."""
    sig, topo, pers = ac.signatures(), ac.topology(), ac.persistence()
    arrays = {"sig_betti": sig.betti, "sig_solid": sig.solid_components,
              "sig_measure": sig.measure, "sig_boundary": sig.boundary_measure,
              "sig_opening": np.array(sig.opening_alpha),
              "topo_vertex_forest": topo.vertex_forest, "topo_dual_forest": topo.dual_forest,
              "topo_dual_edges": topo.dual_edges, "topo_solid_forest": topo.solid_forest,
              "pers_components": pers.components, "pers_cavities": pers.cavities,
              "optimal_alpha": np.array(ac.optimal_alpha()),
              "default_alpha": np.array(ac.default_alpha()),
              "entry_saved": np.array(entry_saved)}
    atomic_write(path, lambda handle: np.savez(handle, **arrays))


def read_topology(path: str | os.PathLike, ac: AlphaComplex) -> TopologyParts:
    """The parts written by write_topology for the same table as ac (lengths checked against
    ac's table: FileFormatError when they do not fit)."""
    with np.load(path, allow_pickle=False) as archive:
        a = {name: archive[name] for name in archive.files}
    levels, dim = ac.index.table.levels, ac.dim
    spectrum = ac.spectrum()
    s, n_cells = len(spectrum), len(levels[dim].enter)
    _expect(a, path, {"sig_betti": (s, dim), "sig_solid": (s,), "sig_measure": (s,),
                      "sig_boundary": (s,), "sig_opening": (), "topo_dual_edges": (None, 2),
                      "pers_components": (None, 2), "pers_cavities": (None, 2),
                      "optimal_alpha": (), "default_alpha": (), "entry_saved": ()})
    _expect_forests(a, path, len(levels[0].enter), n_cells)
    topology = Topology(dim=dim, n_cells=n_cells,
                        enter_sorted=tuple(ascending(level.enter) for level in levels),
                        vertex_forest=readonly(a["topo_vertex_forest"]),
                        dual_forest=readonly(a["topo_dual_forest"]),
                        dual_edges=readonly(a["topo_dual_edges"]),
                        solid_forest=readonly(a["topo_solid_forest"]))
    signatures = Signatures(dim=dim, alphas=spectrum, betti=readonly(a["sig_betti"]),
                            solid_components=readonly(a["sig_solid"]),
                            measure=readonly(a["sig_measure"]),
                            boundary_measure=readonly(a["sig_boundary"]),
                            opening_alpha=float(a["sig_opening"]),
                            intervals=tuple(ac.intervals(k) for k in range(dim + 1)))
    persistence = Persistence(dim=dim, components=readonly(a["pers_components"]),
                              cavities=readonly(a["pers_cavities"]))
    return TopologyParts(topology, signatures, persistence, float(a["optimal_alpha"]),
                         float(a["default_alpha"]), bool(a["entry_saved"]))


def attach(ac: AlphaComplex, parts: TopologyParts) -> AlphaComplex:
    """A complex over ac's own table (points and index shared, nothing copied) that has
    parts' topology and signatures."""
    return AlphaComplex(ac.points, ac.input_index, ac.index, ac.frame, ac.ambient_dim, ac.mode,
                        ac.weights, build_info=ac.build_info, topology=parts.topology,
                        signatures=parts.signatures)


def _expect(a: dict[str, np.ndarray], path, shapes: dict[str, tuple]) -> None:
    """Every named array is there with this shape (None = any length)."""
    for name, shape in shapes.items():
        got = a.get(name)
        if got is None or got.ndim != len(shape) or any(
                want is not None and want != have for want, have in zip(shape, got.shape,
                                                                        strict=True)):
            raise FileFormatError(f"{path}: not this table's topology ({name})")
    for name in ("topo_vertex_forest", "topo_dual_forest", "topo_solid_forest"):
        if a.get(name) is None or a[name].ndim != 1:
            raise FileFormatError(f"{path}: not this table's topology ({name})")


def _expect_forests(a: dict[str, np.ndarray], path, n_vertices: int, n_cells: int) -> None:
    """The forests fit a table of n_vertices and n_cells: a spanning forest has fewer edges
    than nodes, one dual edge per dual-forest value, dual nodes 0..n_cells (n_cells = outside)."""
    edges = a["topo_dual_edges"]
    fits = (len(a["topo_vertex_forest"]) < max(n_vertices, 1)
            and len(a["topo_solid_forest"]) < max(n_cells, 1)
            and len(a["topo_dual_forest"]) == len(edges) <= n_cells
            and (not edges.size or (edges.min() >= 0 and edges.max() <= n_cells)))
    if not fits:
        raise FileFormatError(f"{path}: not this table's topology (forest sizes)")

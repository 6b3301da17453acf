"""The topology of a complex as a small .npz (no pickles): how the topology process hands its
results to the window, which attaches them to its own complex without copying the table.

Arrays: the signatures and forests exactly as a saved table holds them (core/storage/tables.py
`derived_arrays`, read back and checked against the window's table by `read_derived`; files
from before `sig_alphas` was written load too); the persistence pairs `pers_components`,
`pers_cavities` (n, 2) float64; `optimal_alpha` and `default_alpha` () float64; `entry_saved`
() bool (the topology process rewrites the cache entry with them, after this hand-over).
"""

from __future__ import annotations

import os
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from core.arrays import readonly
from core.complex import AlphaComplex
from core.storage.atomic import atomic_write
from core.storage.checks import Checker
from core.storage.npz import read_npz
from core.storage.tables import derived_arrays, read_derived
from core.topology.betti import Topology
from core.topology.persistence import Persistence
from core.topology.signatures import Signatures

SUBJECT = "this table's topology"  # a file that does not fit: "{path}: not this table's ..."


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
    if they are not yet) to path atomically; not the spectrum (`sig_alphas`), which the
    window's table has (94 MB at 1M points)."""
    ac.signatures()
    pers = ac.persistence()
    derived = derived_arrays(ac)
    del derived["sig_alphas"]
    arrays = {**derived, "pers_components": pers.components,
              "pers_cavities": pers.cavities, "optimal_alpha": np.array(ac.optimal_alpha()),
              "default_alpha": np.array(ac.default_alpha()), "entry_saved": np.array(entry_saved)}
    atomic_write(path, lambda handle: np.savez(handle, **arrays))


def read_topology(path: str | os.PathLike, ac: AlphaComplex) -> TopologyParts:
    """The parts written by write_topology for the same table as ac, checked against ac's
    table as a saved table's are (FileFormatError when they do not fit)."""
    check = Checker(Path(path), SUBJECT)
    a = read_npz(path)
    topology, signatures = read_derived(ac, a, check)
    try:
        pairs = [check.array(a[name], name, np.float64, (None, 2))
                 for name in ("pers_components", "pers_cavities")]
        optimal, default = (float(check.array(a[name], name, np.float64, ()))
                            for name in ("optimal_alpha", "default_alpha"))
        entry_saved = bool(check.array(a["entry_saved"], "entry_saved", np.bool_, ()))
    except KeyError as exc:
        raise check.error(f"missing {exc}") from None
    persistence = Persistence(dim=ac.dim, components=readonly(pairs[0]),
                              cavities=readonly(pairs[1]))
    return TopologyParts(topology, signatures, persistence, optimal, default, entry_saved)


def attach(ac: AlphaComplex, parts: TopologyParts) -> AlphaComplex:
    """A complex over ac's own table (points and index shared, nothing copied) that has
    parts' topology and signatures."""
    return AlphaComplex(ac.points, ac.input_index, ac.index, ac.frame, ac.ambient_dim, ac.mode,
                        ac.weights, build_info=ac.build_info, topology=parts.topology,
                        signatures=parts.signatures)

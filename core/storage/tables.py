"""Saving and loading interval tables as .npz (no pickles), with atomic writes.

Arrays (format "alphascoop-table"; the files of version 3 hold them in the compact layout of
core/storage/compact.py, those of versions 1 and 2 as they are, version 1 without
`checksums`; the folders of save_mapped as they are): `points` (m, dim)
float64, `input_index` (n,) int64, `dim`, `ambient_dim`, optional `frame_origin` (3,) /
`frame_basis` (2, 3); for each k in 0..dim: `simplices_k` (n_k, k+1) int32 sorted by enter,
`enter_k`/`regular_k`/`interior_k` (n_k,) float64 radii (inf = never), `face_ids_k`
(n_k, k+1) int32 for k >= 1; `facet_cells` (f, 2) int32 (-1 = outside), `facet_flip` (f,)
bool, `cell_measure` (c,) float64, `facet_interior_order` (f,) int32 (facet rows by
ascending interior).

Weighted tables (tables without it are classic, so older files load unchanged) add `weights`
(m,) float64 squared radii aligned with `points`; their values are signed radii and
`input_index` holds -1 for hidden points.

Optional, written once computed, so re-opening skips the topology pass: `sig_alphas` (s,)
float64 (the spectrum), `sig_betti` (s, dim) int32, `sig_solid` (s,) int32, `sig_measure`,
`sig_boundary` (s,) float64, `sig_opening_pieces` () float64 (the opening alpha,
core.topology.opening; recomputed when absent, as in files that hold only `sig_opening`, the
older one-piece rule);
`topo_vertex_forest`, `topo_dual_forest` (float64),
`topo_dual_edges` (fd, 2) int64, `topo_solid_forest` (float64).

Optional, how the table was built (core/pipeline.py BuildInfo; absent = defaults, so older
tables load): `build_backend` (str, the triangulation backend, "qhull"), and one `build_<field>`
scalar for every other BuildInfo field.

Optional, for a table built in a mode (core/modes/alpha_modes.py; absent = classic): `mode_density`
(int, 0 = off), `mode_combine` (str), `mode_anisotropy` (float), `mode_normals` (str).

Last, `checksums` (core/storage/checksums.py): the CRC-32 of every other member as written. A
file of version 2 or 3 whose members do not match them is damaged (a FileFormatError naming the
member; version 3 checks them before unpacking); version 1 files, which have none, rely on the
array checks alone, which every version passes too, on the unpacked arrays.
"""

from __future__ import annotations

import os
from dataclasses import dataclass
from pathlib import Path
from typing import Protocol

import numpy as np

from core.arrays import readonly
from core.build.levels import Level, Table
from core.build.points import Frame
from core.errors import FileFormatError, InputError
from core.modes.alpha_modes import Mode, make_mode
from core.pipeline import BuildInfo
from core.query.index import TableIndex
from core.storage.atomic import atomic_write
from core.storage.checks import (
    Checker,
    check_forests,
    check_signature_arrays,
    check_signatures,
    check_table,
    scalar,
)
from core.storage.checksums import problem as checksum_problem
from core.storage.checksums import write_npz
from core.storage.compact import pack, unpack
from core.storage.mapped import map_arrays, write_arrays
from core.storage.npz import read_npz
from core.topology.betti import Topology, ascending
from core.topology.opening import opening_alpha_of
from core.topology.signatures import Signatures, level_columns

FORMAT, VERSION = "alphascoop-table", 3
VERSIONS = ("1", "2", "3")  # what `load` reads: version 1 has no checksums, 3 is compact
COMPACT = "3"  # the version whose files hold core.storage.compact's members
OPENING_KEY = "sig_opening_pieces"  # the opening alpha (core.opening) saved with the signatures


class Saveable(Protocol):
    """What `save` reads of a complex (core.complex.AlphaComplex is one)."""

    index: TableIndex
    points: np.ndarray
    input_index: np.ndarray
    frame: Frame | None
    dim: int
    ambient_dim: int
    mode: Mode
    weights: np.ndarray | None
    build_info: BuildInfo
    has_signatures: bool

    def signatures(self) -> Signatures: ...

    def topology(self) -> Topology: ...


@dataclass(frozen=True, eq=False)
class Saved:
    """A table as read back: the arguments of AlphaComplex, with the topology and signatures
    when they were saved (else None)."""

    points: np.ndarray
    input_index: np.ndarray
    index: TableIndex
    frame: Frame | None
    ambient_dim: int
    mode: Mode
    weights: np.ndarray | None
    build_info: BuildInfo
    topology: Topology | None
    signatures: Signatures | None


def _arrays(ac: Saveable) -> dict[str, np.ndarray]:
    """Every array `save` writes (the topology and signatures too once computed)."""
    return {**_header_arrays(ac), **derived_arrays(ac), **_level_arrays(ac.index.table)}


def _header_arrays(ac: Saveable) -> dict[str, np.ndarray]:
    """The table's arrays other than its levels: points, facets, frame, weights, mode, build."""
    table = ac.index.table
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
    out.update(ac.build_info.to_arrays())
    return out


def _level_arrays(table: Table) -> dict[str, np.ndarray]:
    """Each level's simplices, intervals and face ids."""
    out = {}
    for k, level in enumerate(table.levels):
        out[f"simplices_{k}"] = level.simplices
        out[f"enter_{k}"], out[f"regular_{k}"] = level.enter, level.regular
        out[f"interior_{k}"] = level.interior
        if level.face_ids is not None:
            out[f"face_ids_{k}"] = level.face_ids
    return out


def derived_arrays(ac: Saveable) -> dict[str, np.ndarray]:
    """Signatures and topology forests, if `ac` has computed them (never computed here)."""
    if not ac.has_signatures:
        return {}
    sig, topo = ac.signatures(), ac.topology()
    return {"sig_alphas": sig.alphas, "sig_betti": sig.betti, "sig_solid": sig.solid_components,
            "sig_measure": sig.measure, "sig_boundary": sig.boundary_measure,
            OPENING_KEY: np.array(sig.opening_alpha),
            "topo_vertex_forest": topo.vertex_forest, "topo_dual_forest": topo.dual_forest,
            "topo_dual_edges": topo.dual_edges, "topo_solid_forest": topo.solid_forest}


def read_derived(ac: Saveable, a: dict[str, np.ndarray], check: Checker
                 ) -> tuple[Topology, Signatures]:
    """The topology and signatures in `a` (derived_arrays kept apart from the table, as the
    topology process hands them over) checked against ac's table exactly as `load` checks
    saved ones; `sig_alphas` may be absent (it is ac's spectrum). FileFormatError otherwise."""
    spectrum = ac.index.spectrum()
    check.that("sig_alphas" not in a or np.array_equal(a["sig_alphas"], spectrum), "sig_alphas")
    table = {**_header_arrays(ac), **_level_arrays(ac.index.table), "sig_alphas": spectrum}
    merged = {**a, **table}  # the table's own arrays win over any of the same name in `a`
    try:
        check_signature_arrays(check, merged, ac.dim)
        return _derived(ac.index, ac.points, merged, check)
    except KeyError as exc:
        raise check.error(f"missing {exc}") from None


def _derived(index: TableIndex, points: np.ndarray, a: dict[str, np.ndarray], check: Checker
             ) -> tuple[Topology, Signatures]:
    """Saved topology and signatures, once they proved consistent with the table."""
    dim = index.dim
    check_forests(check, a, dim)
    levels = index.table.levels
    topology = Topology(dim=dim, n_cells=len(levels[dim].enter),
                        enter_sorted=tuple(ascending(level.enter) for level in levels),
                        vertex_forest=readonly(a["topo_vertex_forest"]),
                        dual_forest=readonly(a["topo_dual_forest"]),
                        dual_edges=readonly(a["topo_dual_edges"]),
                        solid_forest=readonly(a["topo_solid_forest"]))
    check_signatures(check, a, topology, np.cumsum(a["cell_measure"]))
    opening = (float(a[OPENING_KEY]) if OPENING_KEY in a
               else opening_alpha_of(index, points))
    signatures = Signatures(dim=dim, alphas=readonly(index.spectrum()),
                            betti=readonly(a["sig_betti"]),
                            solid_components=readonly(a["sig_solid"]),
                            measure=readonly(a["sig_measure"]),
                            boundary_measure=readonly(a["sig_boundary"]), opening_alpha=opening,
                            intervals=level_columns(index))
    return topology, signatures


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


def _build_info(a: dict[str, np.ndarray], path: Path) -> BuildInfo:
    """How the saved table was built (defaults for tables saved before BuildInfo)."""
    try:
        return BuildInfo.from_arrays(a)
    except (TypeError, ValueError):
        raise FileFormatError(f"{path}: not a valid Alpha Scoop table (build info)") from None


def save(ac: Saveable, path: str | os.PathLike) -> None:
    """Write `ac` to `path` (.npz) atomically, in the compact layout (core.storage.compact)."""
    members = pack(_arrays(ac))
    atomic_write(path, lambda handle: write_npz(handle, members))


def save_mapped(ac: Saveable, folder: str | os.PathLike) -> bool:
    """Write `ac`'s arrays as `save` names them, one raw .npy each, into folder
    (core.storage.mapped: for other processes to map, as `load` of that folder does); False, with
    nothing written, when the folder's file system lacks the room."""
    return write_arrays(folder, _arrays(ac))


def _read(path: Path, trusted: bool = False) -> dict[str, np.ndarray]:
    """The table's full arrays from the archive (declared sizes checked first; a compact one's
    checksums checked, then unpacked: core.storage.compact), or the folder's mapped arrays
    (save_mapped), if it is one of our tables (`trusted`: core.storage.npz.read_npz's, for a
    file this program has just written)."""
    arrays = map_arrays(path) if path.is_dir() else read_npz(path, trusted=trusted)
    check = Checker(path)
    check.that(str(arrays.get("format", "")) == FORMAT, "missing format tag")
    check.that(arrays.get("version", np.array(-1)).shape == ()
               and str(arrays.get("version")) in VERSIONS, "unknown version")
    if str(arrays["version"]) != COMPACT or path.is_dir():
        return arrays
    if not trusted:  # first: unpacking a damaged member would name the wrong array
        _check_sums(check, arrays)
    check.that("dim" in arrays and arrays["dim"].shape == ()
               and arrays["dim"].dtype.kind in "iu" and int(arrays["dim"]) in (2, 3), "dimension")
    try:
        return unpack(arrays)
    except KeyError as exc:
        raise check.error(f"missing {exc}") from None
    except (IndexError, ValueError, TypeError) as exc:
        raise check.error(f"its arrays do not fit together: {exc}") from None


def _has_sums(path: Path, arrays: dict[str, np.ndarray]) -> bool:
    """True for an archive that records its arrays' checksums (versions 2 and 3), not for a
    version-1 file or a mapped folder."""
    version = str(arrays["version"])
    if path.is_dir() or version == "1":
        return False
    return version == COMPACT or getattr(arrays, "crcs", None) is not None


def _check_sums(check: Checker, arrays: dict[str, np.ndarray]) -> None:
    """A version-2 archive's arrays are the ones written (their CRCs, checked against the
    bytes read, match the checksums written last); folders and version-1 files have none."""
    crcs = getattr(arrays, "crcs", None)
    if crcs is not None and str(arrays["version"]) != "1":
        found = checksum_problem(arrays, crcs)
        check.that(found is None, str(found))


def load(path: str | os.PathLike, *, verify: bool = True, trust_checksums: bool = False,
         spectrum: np.ndarray | None = None) -> Saved:
    """Read a table written by `save` (or the folder written by `save_mapped`, whose arrays
    are mapped read-only, not read: core.storage.mapped); every array is checked
    (core.storage.checks) so that a damaged or crafted file is a FileFormatError, never a wrong
    shape or a crash later.

    verify=False skips the table's array checks and the zip's CRC pass (not the archive's
    sizes, the format tag and the saved topology's checks): only for a file this program
    wrote a moment ago, such as the table a build process hands over, never for a file that
    waited on disk. `spectrum`: the table's (TableIndex.spectrum) as this program found it
    beside the table, used instead of sorting the values again (checked cheaply: a 1-D
    float64 array that ends at the table's last value; a table with its signatures keeps
    theirs). trust_checksums=True (the table cache, whose entries only this program writes):
    an archive whose arrays match the checksums written last is not checked array by array
    again; a file without checksums (version 1) still is."""
    path = Path(path)
    a = _read(path, trusted=not verify)
    check = Checker(path)
    try:
        dim = scalar(check, a["dim"], "dim")
        check.that(dim in (2, 3), "dimension")
        summed = verify and trust_checksums and _has_sums(path, a)
        if summed and str(a["version"]) != COMPACT:  # a compact one's were checked in _read
            _check_sums(check, a)
        if verify and not summed:
            check_table(check, a, dim)
        levels = [Level(a[f"simplices_{k}"], a[f"enter_{k}"], a[f"regular_{k}"],
                        a[f"interior_{k}"], a.get(f"face_ids_{k}")) for k in range(dim + 1)]
        frame = Frame(a["frame_origin"], a["frame_basis"]) if "frame_origin" in a else None
        table = Table(levels, a["facet_cells"], a["facet_flip"], a["cell_measure"],
                      a["facet_interior_order"])
        saved = "sig_alphas" in a
        known = check_signature_arrays(check, a, dim) if saved else None
        index = TableIndex(table, "weights" in a, known)
        if known is None and spectrum is not None:
            check.that(isinstance(spectrum, np.ndarray) and spectrum.ndim == 1
                       and spectrum.dtype == np.float64 and len(spectrum) > 0
                       and float(spectrum[-1]) == index.last_value(), "handed spectrum")
            index = TableIndex(table, "weights" in a, spectrum)
        topology, signatures = (_derived(index, a["points"], a, check) if saved
                                else (None, None))
        mode, build_info = _mode(a, path), _build_info(a, path)
        if verify and not summed and str(a["version"]) != COMPACT:  # last: the checks above
            _check_sums(check, a)                                     # name the array
        return Saved(a["points"], a["input_index"], index, frame, int(a["ambient_dim"]),
                     mode, a.get("weights"), build_info, topology, signatures)
    except KeyError as exc:
        raise check.error(f"missing {exc}") from None

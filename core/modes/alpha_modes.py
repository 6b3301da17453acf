"""Density-scaled and anisotropic alpha (Teichmann & Capps, IEEE Vis 1998) as alpha modes.

A mode changes only the test radius of each Delaunay simplex; the triangulation and which
faces are attached stay the classic (geometric) ones, so the complex is a subcomplex of the
Delaunay triangulation at every alpha. `scaled_table` turns the classic table into the mode's
table, which every query, cursor, signature and export then uses unchanged:

- own value rho(T) of a cell or an unattached face (classic enter < regular): density scaling
  divides T's smallest-circumsphere radius by T's local spacing (the mean or max over its
  vertices of the distance to their k-th nearest neighbour), so alpha counts local spacings;
  anisotropy takes the radius after stretching T along its normal by 1 / (1 - tau), which is
  the alpha test with a ball compressed along the normal to an ellipsoid of half-axis
  (1 - tau) alpha; with both on, the stretched radius is divided by the spacing.
- repair, from the cells down: enter(T) = min(rho(T) if T is unattached, min enter over T's
  cofacets); so a face never enters after its cofaces, attached faces enter with their first
  cofacet as in the classic rule. regular(T) = min enter over cofacets, interior(T) = max
  enter over the cells around T (inf on the convex hull), the classic rules (core.build.table); so
  enter <= regular <= interior and classes are monotone in alpha.
- every level is sorted by its new enter, and the ids that point into it are renumbered
  (core/modes/filtration.py). The classic table a mode starts from is built unsorted and,
  unless the mode is density scaling alone, without its faces' radii (core.build.table's
  build_table sort=False, radii=False: Mode.classic_radii), so the build sorts each level
  once and computes no radii it throws away.
"""

from __future__ import annotations

import threading
from collections.abc import Callable
from concurrent.futures import Future
from dataclasses import dataclass

import numpy as np

from core.build.levels import Table
from core.errors import InputError
from core.geometry.neighbourhood import neighbours, orient, pca_normals, spacing
from core.modes.filtration import repaired, resorted
from core.modes.stretched import stretched_values
from core.progress import Progress

COMBINES = ("mean", "max")
NORMAL_SOURCES = ("estimate", "given")
NORMAL_NEIGHBOURS = 16  #: neighbours of the PCA that estimates normals (8 tilts them
#: where two sheets are closer than their spacing)
ORIENT_NEIGHBOURS = 8  #: nearest of those that link the orientation's spanning tree (a
#: simplex's combined normal does not depend on the signs, only near-ties do: half the
#: graph halves the tree's sort)


@dataclass(frozen=True)
class Mode:
    """How test radii are scaled: density=k (k-th neighbour spacing, None = off) combined
    over a simplex's vertices by `combine`; anisotropy tau in [0, 1) (0 = off) with normals
    "estimate"d by PCA or "given" by the caller. Mode() is the classic alpha."""

    density: int | None = None
    combine: str = "mean"
    anisotropy: float = 0.0
    normals: str = "estimate"

    @property
    def active(self) -> bool:
        """False for the classic alpha (its table is built without this module)."""
        return self.density is not None or self.anisotropy > 0.0

    @property
    def name(self) -> str:
        """'classic', 'density', 'anisotropic' or 'density+anisotropic'."""
        parts = [n for n, on in (("density", self.density is not None),
                                 ("anisotropic", self.anisotropy > 0.0)) if on]
        return "+".join(parts) or "classic"

    @property
    def classic_radii(self) -> bool:
        """Whether the mode's own values start from the classic radii (density scaling
        alone); otherwise its table is built without them (core.build.table.build_table)."""
        return self.density is not None and self.anisotropy == 0.0

    def describe(self) -> str:
        """One line for the info dock, `info` and export metadata."""
        parts = []
        if self.density is not None:
            parts.append(f"density-scaled (k={self.density}, {self.combine}; alpha in local "
                         "spacings)")
        if self.anisotropy > 0.0:
            parts.append(f"anisotropic (tau={self.anisotropy:g}, {self.normals} normals)")
        return ", ".join(parts) or "classic"

    def to_dict(self) -> dict:
        """JSON-ready parameters (the name first)."""
        return {"name": self.name, "density": self.density, "combine": self.combine,
                "anisotropy": self.anisotropy, "normals": self.normals}

    def build_kwargs(self, normals: np.ndarray | None = None) -> dict:
        """The keywords of AlphaComplex.from_points that build in this mode (`normals`, the
        (n, d) array aligned with the points, is passed only for "given" normals)."""
        return {"density": self.density, "combine": self.combine,
                "anisotropy": self.anisotropy,
                "normals": normals if self.normals == "given" else None}

    def key(self) -> str:
        """A canonical text of the parameters ('' for classic), for cache keys."""
        if not self.active:
            return ""
        return f"density={self.density};combine={self.combine};tau={self.anisotropy!r};" \
               f"normals={self.normals}"


def make_mode(density: object = None, combine: object = "mean", anisotropy: object = 0.0,
              normals_given: bool = False) -> Mode:
    """A checked, canonical Mode (unused parameters reset to defaults); InputError otherwise."""
    if density is not None and (isinstance(density, bool) or not isinstance(
            density, (int, np.integer)) or density < 1):
        raise InputError(f"density must be a whole number k >= 1 (neighbours), not {density!r}")
    if combine not in COMBINES:
        raise InputError(f"combine must be 'mean' or 'max', not {combine!r}")
    try:
        tau = float(anisotropy)  # type: ignore[arg-type]
    except (TypeError, ValueError):
        raise InputError(f"anisotropy must be a number in [0, 1), not {anisotropy!r}") from None
    if not 0.0 <= tau < 1.0:
        raise InputError(f"anisotropy must be in [0, 1) (0 = off), not {anisotropy!r}")
    return Mode(None if density is None else int(density),
                str(combine) if density is not None else "mean", tau,
                "given" if normals_given and tau > 0.0 else "estimate")


def point_normals(points: np.ndarray, ids: np.ndarray) -> np.ndarray:
    """(m, d) PCA normals over each point and its neighbours `ids`, oriented consistently."""
    return orient(points, pca_normals(points, ids), ids[:, :ORIENT_NEIGHBOURS])


def _own_values(table: Table, points: np.ndarray, mode: Mode, spacing_: np.ndarray | None,
                normals: np.ndarray | None) -> list[np.ndarray]:
    """Per level: (n_k,) rho of cells and unattached faces, inf for attached faces (0 for
    vertices)."""
    d = len(table.levels) - 1
    if mode.anisotropy > 0.0:
        radii = stretched_values(table, points, normals, mode.anisotropy)
    else:  # the classic radii: a face is attached exactly when enter == regular
        radii = [np.where((level.enter < level.regular) | (k == d), level.enter, np.inf)
                 for k, level in enumerate(table.levels[1:], start=1)]
    out = [np.zeros(len(table.levels[0].simplices))]
    for level, own in zip(table.levels[1:], radii, strict=True):
        if spacing_ is not None:  # cells and unattached faces (attached ones stay inf)
            ids = np.flatnonzero(np.isfinite(own))
            gathered = spacing_[level.simplices[ids]]
            own[ids] /= gathered.max(axis=1) if mode.combine == "max" else gathered.mean(axis=1)
        out.append(own)
    return out


@dataclass(frozen=True, eq=False)
class LocalGeometry:
    """What a mode needs of each point's neighbourhood: (m,) local spacing (density scaling,
    else None) and (m, d) unit normals (anisotropy, else None)."""

    spacing: np.ndarray | None
    normals: np.ndarray | None


def local_geometry(points: np.ndarray, mode: Mode,
                   normals: np.ndarray | None = None) -> LocalGeometry:
    """The spacing and normals of (m, d) `points` for an active `mode`; `normals` (m, d) for
    mode.normals == "given" (else estimated: PCA, oriented)."""
    if len(points) < 2:
        raise InputError("a mode needs at least two points")
    wanted = max(mode.density or 0, NORMAL_NEIGHBOURS if mode.anisotropy > 0.0 else 0)
    dist, ids = neighbours(points, wanted)
    spacing_ = None
    if mode.density is not None:
        spacing_ = spacing(dist[:, : min(mode.density, dist.shape[1])])
    missing = None if normals is None else directionless(normals)
    if mode.anisotropy > 0.0 and (missing is None or missing.any()):
        estimated = point_normals(points, ids[:, :NORMAL_NEIGHBOURS])
        # given normals without a direction (all zero) are estimated too, never left zero
        normals = estimated if missing is None else np.where(missing[:, None], estimated,
                                                             normals)
    return LocalGeometry(spacing_, normals if mode.anisotropy > 0.0 else None)


def directionless(normals: np.ndarray) -> np.ndarray:
    """(n,) bool: the rows of (n, d) normals that give no direction (all zero), whose
    normals the anisotropic mode estimates from the neighbours instead."""
    return ~np.any(normals != 0.0, axis=1)


def local_geometry_beside(points: np.ndarray, mode: Mode,
                          normals: np.ndarray | None = None) -> Callable[[], LocalGeometry]:
    """Start local_geometry in a thread of its own and return the function that waits for
    it (re-raising its error): it needs only the points, so it runs while the classic table
    is built, whose passes leave the second core partly idle."""
    if len(points) < 2:
        raise InputError("a mode needs at least two points")
    future: Future[LocalGeometry] = Future()

    def run() -> None:
        try:
            future.set_result(local_geometry(points, mode, normals))
        except BaseException as exc:  # handed to the waiting caller
            future.set_exception(exc)

    threading.Thread(target=run, name="alphascoop-mode-geometry", daemon=True).start()
    return future.result


def scaled_table(table: Table, points: np.ndarray, mode: Mode, local: LocalGeometry,
                 progress: Progress | None = None) -> Table:
    """The mode's interval table from the classic one of `points` ((m, d) float64, the
    coordinates the table's radii are in) and their `local` geometry. The classic table may
    be unsorted and, unless mode.classic_radii, without its faces' radii (build_table's
    sort=False, radii=False): only its structure and those radii are read. It is consumed:
    core.modes.filtration.resorted sorts it in place, array by array."""
    def step(fraction: float, stage: str) -> None:
        if progress is not None:
            progress(fraction, stage)

    step(0.4, "scaled radii")
    own = _own_values(table, points, mode, local.spacing, local.normals)
    step(0.8, "filtration repair")
    values = repaired(table, own)
    del own  # its arrays are in `values` now, which resorted lets go level by level
    return resorted(table, values)


def file_normals(mode: Mode, attributes: dict, source: str) -> np.ndarray | None:
    """The point file's normals when `mode` wants given normals (None otherwise); an
    InputError naming `source` when the file has none."""
    if mode.normals != "given":
        return None
    normals = attributes.get("normals")
    if normals is None:
        raise InputError(f"{source}: the file has no normals; estimate them instead")
    return np.asarray(normals, dtype=np.float64)


def check_normals(normals: object, n: int, dim: int) -> np.ndarray:
    """(n, dim) float64 normals (any length; 0 = no direction: estimated, local_geometry);
    InputError otherwise."""
    try:
        arr = np.array(normals, dtype=np.float64)
    except (TypeError, ValueError) as exc:
        raise InputError(f"normals must be numbers: {exc}") from None
    if arr.shape != (n, dim):
        raise InputError(f"normals must be an ({n}, {dim}) array like the points, got "
                         f"shape {arr.shape}")
    bad = ~np.isfinite(arr).all(axis=1)
    if bad.any():
        raise InputError(f"{int(bad.sum()):,} of {n:,} normals have NaN or infinite values "
                         f"(the first in row {int(np.argmax(bad))}): fix them, or estimate "
                         "the normals")
    return arr


def unit_rows(vectors: np.ndarray) -> np.ndarray:
    """(n, d) rows scaled to length 1 (zero rows stay zero; rows of any finite size, the
    largest component scaled to 1 first, so no length over- or underflows)."""
    big = np.abs(vectors).max(axis=1, initial=0.0)
    scaled = vectors / np.where(big > 0, big, 1.0)[:, None]
    length = np.sqrt(np.einsum("nd,nd->n", scaled, scaled))
    return scaled / np.where(length > 0, length, 1.0)[:, None]


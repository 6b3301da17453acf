"""The interval table itself, as NPZ (documented layout) or CSV, for analysis elsewhere.

NPZ layout (format "alphascoop-intervals", version 1): `points` (m, dim) float64; `dim`,
`ambient_dim` scalars; for each k in 0..dim: `simplices_k` (n_k, k+1) int32 vertex rows
(ascending within a row; rows ordered by enter) and `intervals_k` (n_k, 3) float64 columns
enter <= regular <= interior (alpha radii; inf = never); `spectrum` (s,) float64; `mode`
the alpha mode as JSON text (core.modes.alpha_modes: its name and parameters; alpha is in its
units). CSV: one row per simplex: k, v0, v1, v2, v3 (-1 = unused), enter, regular, interior.

Weighted tables add `weights` (m,) float64 squared radii and `intervals_sq_k` (squared
values, may be negative) to the NPZ (their `intervals_k` and `spectrum` are signed radii
sign(a2) * sqrt(|a2|)); their CSV has the squared columns enter2, regular2, interior2.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np

from core.export.csvrows import write_rows
from core.export.metadata import mode_metadata

FORMAT, VERSION = "alphascoop-intervals", 1
CSV_HEADER = "k,v0,v1,v2,v3,enter,regular,interior\n"
CSV_HEADER_SQ = "k,v0,v1,v2,v3,enter2,regular2,interior2\n"
CSV_ROW = "%d,%d,%d,%d,%d,%.17g,%.17g,%.17g\n"  # %.17g reads back to the same float64


def table_arrays(ac) -> dict[str, np.ndarray]:
    """The arrays the NPZ holds (see the module docstring)."""
    out = {"format": np.array(FORMAT), "version": np.array(VERSION),
           "points": np.asarray(ac.points), "dim": np.array(ac.dim),
           "ambient_dim": np.array(ac.ambient_dim), "spectrum": np.asarray(ac.spectrum()),
           "mode": np.array(json.dumps(mode_metadata(ac)))}
    for k in range(ac.dim + 1):
        out[f"simplices_{k}"] = np.asarray(ac.simplices(k), dtype=np.int32)
        out[f"intervals_{k}"] = np.asarray(ac.intervals(k), dtype=np.float64)
        if ac.weights is not None:
            out[f"intervals_sq_{k}"] = np.asarray(ac.intervals_sq(k), dtype=np.float64)
    if ac.weights is not None:
        out["weights"] = np.asarray(ac.weights)
    return out


def write_npz(path: Path, ac) -> None:
    """Uncompressed NPZ (fast to load, no pickles)."""
    with open(path, "wb") as fh:
        np.savez(fh, **table_arrays(ac))


def write_csv(path: Path, ac) -> None:
    """One line per simplex, all dimensions, vertices padded with -1 (written in chunks)."""
    with open(path, "w", encoding="utf-8", newline="\n") as fh:
        weighted = ac.weights is not None
        fh.write(CSV_HEADER_SQ if weighted else CSV_HEADER)
        for k in range(ac.dim + 1):
            simp = np.asarray(ac.simplices(k), dtype=np.int64)
            iv = np.asarray(ac.intervals_sq(k) if weighted else ac.intervals(k), dtype=np.float64)
            pad = np.full(len(simp), -1, dtype=np.int64)
            columns = [np.full(len(simp), k, dtype=np.int64), *simp.T, *[pad] * (3 - k), *iv.T]
            write_rows(fh, CSV_ROW, columns)


TABLE_WRITERS = {".npz": write_npz, ".csv": write_csv}

"""The interval table itself, as NPZ (documented layout) or CSV, for analysis elsewhere.

NPZ layout (format "alphascoop-intervals", version 1): `points` (m, dim) float64; `dim`,
`ambient_dim` scalars; for each k in 0..dim: `simplices_k` (n_k, k+1) int32 vertex rows
(ascending within a row; rows ordered by enter) and `intervals_k` (n_k, 3) float64 columns
enter <= regular <= interior (alpha radii; inf = never); `spectrum` (s,) float64.
CSV: one row per simplex: k, v0, v1, v2, v3 (-1 = unused), enter, regular, interior.
"""

from __future__ import annotations

import io
from pathlib import Path

import numpy as np

FORMAT, VERSION = "alphascoop-intervals", 1


def table_arrays(ac) -> dict[str, np.ndarray]:
    """The arrays the NPZ holds (see the module docstring)."""
    out = {"format": np.array(FORMAT), "version": np.array(VERSION),
           "points": np.asarray(ac.points), "dim": np.array(ac.dim),
           "ambient_dim": np.array(ac.ambient_dim), "spectrum": np.asarray(ac.spectrum())}
    for k in range(ac.dim + 1):
        out[f"simplices_{k}"] = np.asarray(ac.simplices(k), dtype=np.int32)
        out[f"intervals_{k}"] = np.asarray(ac.intervals(k), dtype=np.float64)
    return out


def write_npz(path: Path, ac) -> None:
    """Uncompressed NPZ (fast to load, no pickles)."""
    with open(path, "wb") as fh:
        np.savez(fh, **table_arrays(ac))


def write_csv(path: Path, ac) -> None:
    """One line per simplex, all dimensions, vertices padded with -1."""
    with open(path, "w", encoding="utf-8", newline="\n") as fh:
        fh.write("k,v0,v1,v2,v3,enter,regular,interior\n")
        for k in range(ac.dim + 1):
            simp = np.full((len(ac.simplices(k)), 4), -1, dtype=np.int64)
            simp[:, : k + 1] = ac.simplices(k)
            block = np.column_stack([np.full(len(simp), k), simp])
            buf = io.StringIO()
            np.savetxt(buf, block, fmt="%d", delimiter=",")
            ints = buf.getvalue().splitlines()
            buf = io.StringIO()
            np.savetxt(buf, np.asarray(ac.intervals(k)), fmt="%.17g", delimiter=",")
            floats = buf.getvalue().splitlines()
            fh.writelines(f"{a},{b}\n" for a, b in zip(ints, floats, strict=True))


TABLE_WRITERS = {".npz": write_npz, ".csv": write_csv}

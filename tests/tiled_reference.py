"""The in-memory answer in global ids, to compare tiled shapes with simplex for simplex."""

from __future__ import annotations

import numpy as np

from core import AlphaComplex


def global_ids(ac: AlphaComplex) -> np.ndarray:
    """(m,) smallest input row of each point of the complex (the tiles' global ids)."""
    index = np.asarray(ac.input_index)
    ids = np.full(len(ac.points), np.iinfo(np.int64).max)
    seen = index >= 0
    np.minimum.at(ids, index[seen], np.flatnonzero(seen))
    return ids


def members(ac: AlphaComplex, at: dict) -> list[tuple[np.ndarray, np.ndarray]]:
    """Per dimension: (simplices in global ids, sorted rows and lexicographic order; their
    classes) of the complex at `at`."""
    ids = global_ids(ac)
    out = []
    for k in range(ac.dim + 1):
        cls = np.asarray(ac.classify(k=k, **at))
        inside = cls > 0
        rows = np.sort(ids[np.asarray(ac.simplices(k))[inside]], axis=1)
        order = np.lexsort(rows.T[::-1])
        out.append((rows[order], cls[inside][order]))
    return out


def differences(ac: AlphaComplex, tiled, at: dict) -> list[str]:
    """What differs between the in-memory complex at `at` and the tiled shape (empty: the
    same simplices in every dimension with the same classes)."""
    problems = []
    if tiled.dim != ac.dim:
        return [f"dimension {tiled.dim} != {ac.dim}"]
    for k, (rows, cls) in enumerate(members(ac, at)):
        mine = tiled.ids[tiled.simplices[k]]
        order = np.lexsort(mine.T[::-1])
        mine, classes = mine[order], tiled.classes[k][order]
        if mine.shape != rows.shape or not np.array_equal(mine, rows):
            a = {tuple(r) for r in rows.tolist()}
            b = {tuple(r) for r in mine.tolist()}
            problems.append(f"k={k}: {len(a - b)} only in memory, {len(b - a)} only tiled")
        elif not np.array_equal(classes, cls):
            problems.append(f"k={k}: {int(np.sum(classes != cls))} classes differ")
    return problems


def mid_gap_alpha(ac: AlphaComplex, quantile: float) -> float:
    """An alpha strictly between two consecutive critical values near `quantile` of the
    spectrum (no simplex enters exactly at it)."""
    spectrum = np.asarray(ac.spectrum())
    spectrum = spectrum[spectrum > 0]
    i = min(int(quantile * len(spectrum)), len(spectrum) - 2)
    return float(np.sqrt(spectrum[i] * spectrum[i + 1]))


def same_info(tiled: dict, memory: dict) -> list[str]:
    """What differs between `info --tiled --json` and the in-memory `info --json` of the same
    file at the same alpha (empty: the same counts per class, components, volume, points)."""
    problems = [f"{name}: {tiled['classes'].get(name)} != {counts}"
                for name, counts in memory["classes"].items()
                if tiled["classes"].get(name) != {**counts, "exterior": None}]
    if tiled["components"] != memory["betti"][0]:
        problems.append(f"components {tiled['components']} != {memory['betti'][0]}")
    if not np.isclose(tiled["volume"], memory["volume"], rtol=1e-9, atol=0.0):
        problems.append(f"volume {tiled['volume']} != {memory['volume']}")
    if tiled["points"] != memory["load"]["n_points"]:
        problems.append(f"points {tiled['points']} != {memory['load']['n_points']}")
    return problems


"""A molecule's pockets written out: a VTU of their tetrahedra and mouth triangles with cell
data `pocket` (0 = largest) and `mouth` (-1 on tetrahedra), and a CSV of the residues lining
each pocket (one row per pocket and residue: its atoms and their lining area)."""

from __future__ import annotations

import csv
from pathlib import Path

import numpy as np

from core.export.vtkxml import vtu_bytes
from core.storage.atomic import atomic_path

POCKET_FORMATS = {".vtu": "VTU: the pockets' tetrahedra and mouths (cell data pocket, mouth)",
                  ".csv": "CSV: the residues lining each pocket"}
CSV_COLUMNS = ("pocket", "volume", "area", "mouths", "chain", "residue", "number", "atoms",
               "lining_area")


def write_pockets_vtu(path: str | Path, ac, pockets, meta: dict | None = None) -> int:
    """Write the pockets (core.molecule.pockets.Pockets of `ac`) as VTU; the cell count."""
    cells = np.flatnonzero(pockets.cells >= 0)
    tets = np.asarray(ac.simplices(3))[cells]
    tris = np.asarray(ac.simplices(2))[pockets.facets]
    data = {"pocket": np.concatenate([pockets.cells[cells],
                                      pockets.mouth_pocket[pockets.facet_mouth]]).astype(np.int32),
            "mouth": np.concatenate([np.full(len(tets), -1), pockets.facet_mouth]).astype(np.int32)}
    blocks = [b for b in (tets, tris) if len(b)] or [np.empty((0, 1), np.int64)]
    points = np.asarray(ac.to_ambient(ac.points), np.float64)
    with atomic_path(path) as tmp:
        tmp.write_bytes(vtu_bytes(points, blocks, data, meta or {}))
    return len(tets) + len(tris)


def residue_rows(pockets, labels: list[dict]) -> list[dict]:
    """CSV rows: per pocket (largest first) its residues in order of first lining atom (by
    lining area), with the atom names and their summed lining area."""
    rows = []
    for p in range(len(pockets)):
        by_residue: dict[tuple, dict] = {}
        area_row = pockets.atom_area.getrow(p).toarray().ravel()
        for a in pockets.atoms[p]:
            lab = labels[int(a)]
            key = (lab["chain"], lab["residue"], lab["number"])
            row = by_residue.setdefault(key, {
                "pocket": p, "volume": f"{pockets.volume[p]:.6g}",
                "area": f"{pockets.area[p]:.6g}", "mouths": len(pockets.mouths(p)),
                "chain": key[0], "residue": key[1], "number": key[2], "atoms": [],
                "lining_area": 0.0})
            row["atoms"].append(lab["atom"])
            row["lining_area"] += float(area_row[int(a)])
        for row in by_residue.values():
            row["atoms"] = " ".join(row["atoms"])
            row["lining_area"] = f"{row['lining_area']:.6g}"
            rows.append(row)
    return rows


def write_pockets_csv(path: str | Path, pockets, labels: list[dict]) -> int:
    """Write the lining residues of every pocket as CSV; the row count."""
    rows = residue_rows(pockets, labels)
    with atomic_path(path) as tmp, open(tmp, "w", newline="", encoding="utf-8") as out:
        writer = csv.DictWriter(out, fieldnames=CSV_COLUMNS)
        writer.writeheader()
        writer.writerows(rows)
    return len(rows)


def label_dicts(labels) -> list[dict]:
    """Dataset.atom_labels ('chain:residue:number:atom' per point) as atom_labels' dicts."""
    out = []
    for text in labels:
        chain, residue, number, atom = [*str(text).split(":"), "", "", "", ""][:4]
        out.append({"chain": chain, "residue": residue, "number": number, "atom": atom})
    return out


def write_pockets_file(dataset, path: str | Path) -> str:
    """Write an open molecule's pockets to .vtu or .csv; the status line."""
    pockets = dataset.molecule.pockets
    if Path(path).suffix.lower() == ".csv":
        count = write_pockets_csv(path, pockets, label_dicts(dataset.atom_labels))
        return f"{path}: {len(pockets)} pockets, {count:,} lining residues"
    count = write_pockets_vtu(path, dataset.ac, pockets, {"probe": dataset.molecule.probe})
    return f"{path}: {len(pockets)} pockets, {count:,} cells (cell data pocket, mouth)"

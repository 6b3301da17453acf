"""A molecule's pockets in the window: their tetrahedra and mouth triangles as arrays with a
colour per pocket (the scene draws them), and the text of a clicked pocket (its residues)."""

from __future__ import annotations

import html
from dataclasses import dataclass

import numpy as np

#: one colour per pocket, largest first, cycling after the tenth (Tableau 10)
POCKET_COLOURS = ("#4e79a7", "#e15759", "#59a14f", "#b07aa1", "#76b7b2", "#edc948",
                  "#ff9da7", "#9c755f", "#f28e2b", "#bab0ac")
RESIDUES_SHOWN = 60  # residues listed for a clicked pocket (the CSV export has them all)


@dataclass(frozen=True)
class PocketArrays:
    """cells (k, 4) int32 pocket tetrahedra and cell_rgb (k, 3) uint8; mouths (f, 3) int32
    mouth triangles and mouth_rgb (f, 3) uint8 (rows of the complex's points)."""

    cells: np.ndarray
    cell_rgb: np.ndarray
    mouths: np.ndarray
    mouth_rgb: np.ndarray


def pocket_rgb(ids: np.ndarray) -> np.ndarray:
    """(k, 3) uint8 colour of each pocket id (POCKET_COLOURS, cycling)."""
    table = np.array([[int(c[i:i + 2], 16) for i in (1, 3, 5)] for c in POCKET_COLOURS],
                     dtype=np.uint8)
    return table[np.asarray(ids, np.int64) % len(table)]


def pocket_arrays(ac, pockets) -> PocketArrays:
    """The drawn arrays of `pockets` (core.molecule.pockets.Pockets of `ac`)."""
    rows = np.flatnonzero(pockets.cells >= 0)
    owner = pockets.mouth_pocket[pockets.facet_mouth]
    return PocketArrays(
        cells=np.asarray(ac.simplices(3), np.int32)[rows],
        cell_rgb=pocket_rgb(pockets.cells[rows]),
        mouths=np.asarray(ac.simplices(2), np.int32)[pockets.facets],
        mouth_rgb=pocket_rgb(owner))


def pocket_at(pockets, k: int, row: int) -> int | None:
    """The pocket of the k-simplex `row` (a pocket cell or a mouth triangle), else None."""
    if k == 3 and 0 <= row < len(pockets.cells) and pockets.cells[row] >= 0:
        return int(pockets.cells[row])
    if k == 2:
        hit = np.flatnonzero(pockets.facets == row)
        if len(hit):
            return int(pockets.mouth_pocket[pockets.facet_mouth[hit[0]]])
    return None


def pocket_text(pockets, pocket: int, labels: np.ndarray | None) -> str:
    """Rich text for one pocket: its measures, mouths and lining residues (`labels` (m,) str
    'chain:residue:number:atom' per point, None: atom rows)."""
    mouths = pockets.mouths(pocket)
    head = (f"<b>pocket {pocket + 1} of {len(pockets)}</b>: {pockets.volume[pocket]:.4g} Å³, "
            f"{pockets.area[pocket]:.4g} Å², {len(mouths)} mouth"
            f"{'' if len(mouths) == 1 else 's'} ("
            + ", ".join(f"{pockets.mouth_area[m]:.3g} Å²" for m in mouths) + ")")
    atoms = pockets.atoms[pocket]
    if labels is None:
        return head + "<br>atoms " + ", ".join(str(int(a)) for a in atoms[:RESIDUES_SHOWN])
    parts = [str(labels[a]).split(":")[:3] for a in atoms]
    residues = list(dict.fromkeys(" ".join(p for p in part if p) for part in parts))
    noun = "residues" if any(len(part) > 1 and part[1] for part in parts) else "atoms"  # XYZR
    more = len(residues) - RESIDUES_SHOWN
    return (head + f"<br>{len(residues)} {noun}: "
            + html.escape(", ".join(residues[:RESIDUES_SHOWN]))
            + (f" … and {more} more" if more > 0 else ""))

"""A molecule's measures from its weighted alpha complex: exact area and volume of the union
of its balls, per-atom exposed area, its cavities (voids) and its pockets, each with its exact
volume and lining area (`regions`, `pockets`)."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from core.arrays import contiguous_readonly
from core.errors import InputError
from core.molecule.cavities import void_cells
from core.molecule.measures import dual_simplices, union_measures
from core.molecule.pockets import Pockets, find_pockets
from core.molecule.regions import dual_facts, lining_atoms, region_measures


@dataclass(frozen=True, eq=False)
class MoleculeMeasures:
    """Measures of the union of atom balls at alpha² = `alpha2` (0: the balls themselves).

    atom_area (n,) float64 exposed area of each input atom (0 for hidden ones), point_area
    (m,) the same aligned with the complex's points (exports' point data); cavities (k,)
    float64 exact volume of the empty space of each void, largest first, cavity_areas (k,)
    the surface lining each, cavity_atoms their lining balls (rows of the complex's points);
    cavity_errors (k,) zeros (the values are exact; kept for the JSON's readers);
    cavity_cells (n_cells,) int64 void label of each cell of the complex (-1 = none);
    pockets the Pockets (core.molecule.pockets).
    """

    atoms: int
    probe: float
    alpha2: float
    surface_area: float
    volume: float
    atom_area: np.ndarray
    point_area: np.ndarray
    cavities: np.ndarray
    cavity_errors: np.ndarray
    cavity_cells: np.ndarray
    cavity_areas: np.ndarray
    cavity_atoms: tuple
    pockets: Pockets

    def to_dict(self, labels: list[dict] | None = None) -> dict:
        """The JSON `molecule` object of `alphascoop info`; `labels` (m,) names each point of
        the complex (chain, residue, number, atom) for the pockets' lining atoms."""
        return {"atoms": self.atoms, "probe": self.probe, "alpha2": self.alpha2,
                "surface_area": self.surface_area, "volume": self.volume,
                "cavities": [float(v) for v in self.cavities],
                "cavity_errors": [float(e) for e in self.cavity_errors],
                "cavity_areas": [float(a) for a in self.cavity_areas],
                "atom_area": [round(float(a), 6) for a in self.atom_area],
                "pockets": pocket_dicts(self.pockets, labels)}


def pocket_dicts(pockets: Pockets, labels: list[dict] | None = None) -> list[dict]:
    """`molecule.pockets`: largest first, each with volume, area, mouths (area, perimeter,
    largest first) and lining atoms (labels[row], else {"point": row})."""
    out = []
    for p in range(len(pockets)):
        mouths = pockets.mouths(p)
        mouths = mouths[np.argsort(-pockets.mouth_area[mouths], kind="stable")]
        out.append({
            "volume": float(pockets.volume[p]), "area": float(pockets.area[p]),
            "mouths": [{"area": float(pockets.mouth_area[m]),
                        "perimeter": float(pockets.mouth_perimeter[m])} for m in mouths],
            "atoms": [labels[int(a)] if labels is not None else {"point": int(a)}
                      for a in pockets.atoms[p]]})
    return out


def measure_molecule(ac, probe: float, alpha2: float = 0.0,
                     check: Callable[[], None] | None = None) -> MoleculeMeasures:
    """Area, volume, per-atom area and cavities of a weighted 3D AlphaComplex's balls.

    At alpha² = 0 the complex is the dual of the union of balls of radii sqrt(weights);
    another alpha² measures the balls grown to squared radii weights + alpha². `check()` is
    called between the stages and may raise (core.errors.Cancelled) to stop.
    """
    check = check or (lambda: None)
    if ac.weights is None or ac.dim != 3:
        raise InputError("molecule measures need a weighted 3D complex (atoms as balls)")
    if ac.weights.min() + alpha2 <= 0:
        raise InputError(f"alpha2 {alpha2:g} leaves some balls with no radius")
    radii = np.sqrt(ac.weights + alpha2)
    simplices = dual_simplices(ac, alpha2)
    union = union_measures(ac.points, radii, *simplices[1:], vertices=simplices[0][:, 0])
    check()
    facts = dual_facts(ac, alpha2)
    labels = void_cells(~facts.cell_in, facts.facet_cells, ~facts.facet_in)
    voids = region_measures(facts, labels, int(labels.max()) + 1 if len(labels) else 0)
    check()
    pockets = find_pockets(facts)
    volumes = voids.volume
    order = np.argsort(-volumes, kind="stable")
    relabel = np.full(len(order) + 1, -1)
    relabel[order] = np.arange(len(order))
    atom_area = np.where(ac.input_index >= 0, union.atom_area[np.maximum(ac.input_index, 0)], 0)
    return MoleculeMeasures(
        atoms=len(ac.input_index), probe=float(probe), alpha2=float(alpha2),
        surface_area=union.area, volume=union.volume, atom_area=contiguous_readonly(atom_area),
        point_area=union.atom_area,
        cavities=contiguous_readonly(volumes[order]),
        cavity_errors=contiguous_readonly(np.zeros(len(order))),
        cavity_cells=contiguous_readonly(relabel[labels]),
        cavity_areas=contiguous_readonly(voids.area[order]),
        cavity_atoms=tuple(lining_atoms(voids, int(v)) for v in order),
        pockets=pockets)

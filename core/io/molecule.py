"""PDB and mmCIF molecules (gzip too) through gemmi: atoms as balls with van der Waals radii;
PQR and XYZR files with their own radii (`radii_files`).

First model only, the first alternate location (drop_other_conformers), waters dropped unless
asked for, hydrogens kept.
Radii: gemmi's `Element.vdw_r` (Bondi 1964 for H, C, N, O, S, P and the halogens; other
elements from the same table gemmi ships); an unknown element ('X', or a radius gemmi does not
know) gets UNKNOWN_RADIUS and is named in the report.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass
from pathlib import Path

import numpy as np

from core.errors import FileFormatError
from core.io.radii_files import AtomTable, read_pqr, read_xyzr
from core.io.report import PointSet, finish

MOLECULE_EXTENSIONS = (".pdb", ".ent", ".cif", ".mmcif", ".pqr", ".xyzr")
RADII_READERS = {".pqr": read_pqr, ".xyzr": read_xyzr}  # the file gives every atom's radius
DEFAULT_PROBE = 1.4  # Å, a water molecule
UNKNOWN_RADIUS = 1.8  # Å, for elements without a known van der Waals radius


@dataclass(frozen=True)
class MoleculeReport:
    """What the molecule reader found and skipped."""

    path: str
    models: int
    chains: int
    residues: int
    atoms: int
    hydrogens: int
    waters_skipped: int
    altlocs_skipped: int
    unknown_elements: tuple[str, ...] = ()

    def to_dict(self) -> dict:
        out = asdict(self)
        out["unknown_elements"] = list(self.unknown_elements)
        return out

    def summary(self) -> str:
        """One sentence: what was read and what was skipped."""
        skipped = (f"{self.waters_skipped:,} water atoms and {self.altlocs_skipped:,} "
                   f"alternate-location atoms skipped")
        extra = (f"; unknown elements {', '.join(self.unknown_elements)} given radius "
                 f"{UNKNOWN_RADIUS} Å" if self.unknown_elements else "")
        groups = (f"{_count(self.residues, 'residue')}, {_count(self.chains, 'chain')}"
                  if self.chains else "no residues or chains in the file")  # XYZR
        return (f"{_count(self.atoms, 'atom')} ({self.hydrogens:,} H), {groups}, "
                f"model 1 of {self.models}; {skipped}{extra}")


def _count(count: int, noun: str) -> str:
    """'1 chain', '2 chains'."""
    return f"{count:,} {noun}{'' if count == 1 else 's'}"


@dataclass(frozen=True, eq=False)
class Molecule:
    """Atoms of one model: centres (n, 3) float64 Å, elements (n,) str, vdw_radii (n,) float64,
    atomic_numbers (n,) int16, residues (n,) str labels 'chain:name:number', atom_names (n,)
    str ('CA'...; None when the file names none)."""

    centres: np.ndarray
    elements: np.ndarray
    atomic_numbers: np.ndarray
    vdw_radii: np.ndarray
    residues: np.ndarray
    report: MoleculeReport
    atom_names: np.ndarray | None = None

    def radii(self, probe: float = DEFAULT_PROBE) -> np.ndarray:
        """(n,) float64 ball radii: van der Waals radius plus the probe (0 = vdW surface)."""
        return self.vdw_radii + probe

    def weights(self, probe: float = DEFAULT_PROBE) -> np.ndarray:
        """(n,) float64 squared ball radii, the weights of the weighted alpha complex."""
        return self.radii(probe) ** 2


def molecule_extension(path: Path) -> str | None:
    """'.pdb', '.cif'... for a molecule file (also 'x.pdb.gz'), else None."""
    suffixes = [s.lower() for s in path.suffixes[-2:]]
    if suffixes and suffixes[-1] == ".gz":
        suffixes = suffixes[:-1]
    return suffixes[-1] if suffixes and suffixes[-1] in MOLECULE_EXTENSIONS else None


def _structure(path: Path, ext: str):
    """gemmi's Structure of the file; parser failures become a FileFormatError."""
    import gemmi

    fmt = gemmi.CoorFormat.Pdb if ext in (".pdb", ".ent") else gemmi.CoorFormat.Mmcif
    try:
        return gemmi.read_structure(str(path), format=fmt)
    except (RuntimeError, ValueError) as exc:
        raise FileFormatError(f"{path}: unreadable {ext.lstrip('.').upper()} file "
                              f"({str(exc).splitlines()[0] if str(exc) else type(exc).__name__})"
                              ) from None


def drop_other_conformers(model) -> int:
    """Remove from the gemmi `model` the atoms of alternate conformations other than the one
    kept; returns how many went. Only atoms whose altloc is set may go: in each residue
    position (chain, number, insertion code) the first altloc met is kept, with every atom
    that has none. Atoms that merely share a name (ligands written with one name per
    element, residues numbered alike) all stay: gemmi's remove_alternative_conformations
    keeps one atom per name, and so dropped them. A model without altlocs (gemmi counts the
    atoms whose altloc is empty, selection ':') is left as it is without a pass over its atoms."""
    import gemmi

    if model.count_atom_sites(gemmi.Selection(":")) == model.count_atom_sites():
        return 0
    kept: dict[tuple[str, str], str] = {}
    removed = 0
    for chain in model:
        for residue in chain:
            position = (chain.name, str(residue.seqid))
            alts = [atom.altloc for atom in residue]  # "\0": none (gemmi's has_altloc)
            first = kept.get(position) or next((a for a in alts if a != "\0"), "")
            kept[position] = first
            for i in range(len(alts) - 1, -1, -1):
                if alts[i] not in ("\0", first):
                    del residue[i]
                    removed += 1
        for i in range(len(chain) - 1, -1, -1):
            if len(chain[i]) == 0:  # a residue made only of another conformer
                del chain[i]
    return removed


def read_molecule(path: str | Path, *, keep_water: bool = False) -> Molecule:
    """Read the first model of a PDB/mmCIF file (optionally gzipped) into a Molecule."""
    path = Path(path)
    ext = molecule_extension(path)
    if ext is None:
        raise FileFormatError(f"{path}: not a molecule file (known: "
                              f"{' '.join(MOLECULE_EXTENSIONS)}, optionally .gz)")
    if not path.is_file():
        raise FileFormatError(f"{path}: no such file")
    if ext in RADII_READERS:
        return _from_table(path, RADII_READERS[ext](path, keep_water))
    st = _structure(path, ext)
    try:
        return _cleaned(path, st, keep_water)
    except UnicodeDecodeError:  # gemmi hands names over as UTF-8 text
        raise FileFormatError(f"{path}: unreadable {ext.lstrip('.').upper()} file (names of "
                              "atoms, residues or chains that are not text)") from None


def _cleaned(path: Path, st, keep_water: bool) -> Molecule:
    """The first model of `st`, other conformers and (unless kept) waters removed."""
    n_models = len(st)
    if n_models == 0:
        raise FileFormatError(f"{path}: no atoms (no model in the file)")
    for extra in range(n_models - 1, 0, -1):
        del st[extra]
    altlocs = drop_other_conformers(st[0])
    waters = sum(len(res) for chain in st[0] for res in chain if res.is_water())
    if not keep_water:
        st.remove_waters()
    else:
        waters = 0
    st.remove_empty_chains()
    return _molecule(path, st, n_models, waters, altlocs)


def _from_table(path: Path, t: AtomTable) -> Molecule:
    """The Molecule of a radii file's atoms (PQR, XYZR)."""
    report = MoleculeReport(path=str(path), models=t.models, chains=t.chains,
                            residues=len(set(t.residues.tolist())), atoms=len(t.radii),
                            hydrogens=int((t.numbers == 1).sum()), waters_skipped=t.waters,
                            altlocs_skipped=0)
    return Molecule(t.centres, t.elements, t.numbers, t.radii, t.residues, report, t.names)


def _molecule(path: Path, st, n_models: int, waters: int, altlocs: int) -> Molecule:
    """Flatten the (cleaned) first model into arrays and the report: one pass over the atoms
    (position, element, name); residue labels made once per residue, element numbers and
    radii once per element."""
    model = st[0]
    positions, elements, names, labels, sizes = [], [], [], [], []
    for chain in model:
        for res in chain:
            labels.append(f"{chain.name}:{res.name}:{res.seqid.num}{res.seqid.icode.strip()}")
            sizes.append(len(res))
            for atom in res:
                positions.append(atom.pos.tolist())
                elements.append(atom.element.name)
                names.append(atom.name)
    if not positions:
        raise FileFormatError(f"{path}: no atoms (after skipping {waters:,} water atoms)")
    centres = np.array(positions, dtype=np.float64)
    kinds, kind_of = np.unique(np.array(elements), return_inverse=True)
    known = [_element(str(kind)) for kind in kinds]
    numbers = np.array([number for number, _ in known], dtype=np.int16)[kind_of]
    # gemmi stores radii as float32: round back to the table's 2-3 decimals
    radii = np.round(np.array([radius for _, radius in known], dtype=np.float64), 3)[kind_of]
    unknown = (numbers == 0) | ~(radii > 0)
    radii[unknown] = UNKNOWN_RADIUS
    residues = np.repeat(np.array(labels), sizes)
    if not np.all(np.isfinite(centres)):
        raise FileFormatError(f"{path}: non-finite atom coordinates")
    elements = kinds[kind_of]
    report = MoleculeReport(
        path=str(path), models=n_models, chains=len(model), residues=len(labels),
        atoms=len(centres), hydrogens=int((numbers == 1).sum()), waters_skipped=waters,
        altlocs_skipped=altlocs,
        unknown_elements=tuple(sorted({str(e) for e in elements[unknown]})))
    return Molecule(centres, elements, numbers, radii, residues, report, np.array(names))


def _element(name: str) -> tuple[int, float]:
    """(atomic number, van der Waals radius) of gemmi's element `name` (as float32)."""
    import gemmi

    element = gemmi.Element(name)
    return element.atomic_number, element.vdw_r


def atom_labels(mol: Molecule, points: np.ndarray) -> list[dict]:
    """For each of `points` (m, 3) (a complex's atoms), the nearest atom of `mol` as
    {"chain", "residue", "number", "atom", "index"} (index: its row in the file's atoms)."""
    from scipy.spatial import cKDTree

    _, rows = cKDTree(mol.centres).query(np.asarray(points, np.float64))
    out = []
    for row in np.asarray(rows, np.int64):
        chain, name, number = [*str(mol.residues[row]).split(":"), "", ""][:3]
        atom = str(mol.atom_names[row]) if mol.atom_names is not None else str(
            mol.elements[row])
        out.append({"chain": chain, "residue": name, "number": number, "atom": atom,
                    "index": int(row)})
    return out


def molecule_attributes(mol: Molecule, probe: float = DEFAULT_PROBE) -> dict[str, np.ndarray]:
    """Per-atom attributes of a molecule's point set: `vdw_radius`, `atomic_number` and
    `weights` (squared ball radius with the probe)."""
    return {"vdw_radius": mol.vdw_radii, "atomic_number": mol.atomic_numbers,
            "weights": mol.weights(probe)}


def read_molecule_pointset(path: str | Path, *, probe: float = DEFAULT_PROBE,
                           keep_water: bool = False) -> tuple[PointSet, Molecule]:
    """(PointSet of the atoms with molecule_attributes for `probe`, the Molecule read)."""
    mol = read_molecule(path, keep_water=keep_water)
    ext = molecule_extension(Path(path)) or ""
    ps = finish(Path(path), ext.lstrip(".").upper(), mol.centres,
                molecule_attributes(mol, probe), notes=(mol.report.summary(),),
                weights_from=f"atoms: (van der Waals radius + probe {probe:g} Å)²")
    return ps, mol


def read_molecule_points(path: Path, columns: object) -> tuple[np.ndarray, dict, tuple]:
    """The point-reader view of a molecule (see molecule_attributes; default probe)."""
    if columns is not None:
        raise FileFormatError(f"{path}: --columns does not apply to molecule files")
    mol = read_molecule(path)
    return mol.centres, molecule_attributes(mol), (mol.report.summary(),)

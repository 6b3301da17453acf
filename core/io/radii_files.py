"""Molecules whose files carry each atom's radius: PQR (PDB2PQR, APBS) and XYZR (MSMS).

PQR: whitespace-separated ATOM/HETATM records `serial name resName [chain] resSeq x y z
charge radius` (the chain is optional); the first model only (ENDMDL ends it); waters (HOH,
WAT) skipped unless asked for. XYZR: one atom per line, `x y z radius` and optionally a name
after them; '#' starts a comment. The radii are the file's; the probe is added as for PDB.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from core.errors import FileFormatError

WATERS = ("HOH", "WAT", "H2O", "DOD", "SOL")


@dataclass(frozen=True, eq=False)
class AtomTable:
    """What a radii file gives, for core.io.molecule to make a Molecule of: centres (n, 3),
    radii (n,) float64, elements (n,) str, numbers (n,) int16, residues (n,) str
    'chain:name:number', names (n,) str, and the counts of its report."""

    centres: np.ndarray
    radii: np.ndarray
    elements: np.ndarray
    numbers: np.ndarray
    residues: np.ndarray
    names: np.ndarray
    waters: int
    models: int
    chains: int


def _element_of(name: str) -> tuple[str, int]:
    """(element symbol, atomic number) guessed from a PDB-style atom name ('CA' -> C)."""
    import gemmi

    letters = "".join(ch for ch in name if ch.isalpha())
    for guess in (letters[:1], letters[:2]):
        el = gemmi.Element(guess) if guess else None
        if el is not None and el.atomic_number > 0:
            return el.name, el.atomic_number
    return "X", 0


def _pqr_rows(path: Path, keep_water: bool) -> tuple[list[tuple], int, int]:
    """(atom rows (chain, resname, resseq, name, x, y, z, r), waters skipped, models read)."""
    rows, waters, models = [], 0, 1
    with open(path, encoding="utf-8", errors="replace") as handle:
        for number, line in enumerate(handle, 1):
            if line.startswith("ENDMDL"):
                break
            if not line.startswith(("ATOM", "HETATM")):
                continue
            f = line.split()
            if len(f) not in (10, 11):
                raise FileFormatError(f"{path}: line {number}: a PQR atom needs 10 or 11 "
                                      f"fields, got {len(f)}")
            try:
                x, y, z, _, r = map(float, f[-5:])
            except ValueError:
                raise FileFormatError(f"{path}: line {number}: coordinates, charge and radius "
                                      "must be numbers") from None
            chain = f[4] if len(f) == 11 else ""
            if f[3] in WATERS and not keep_water:
                waters += 1
                continue
            rows.append((chain, f[3], f[-6], f[2], x, y, z, r))
    return rows, waters, models


def read_pqr(path: Path, keep_water: bool = False) -> AtomTable:
    """The atoms of a PQR file (radii from its last column)."""
    rows, waters, models = _pqr_rows(path, keep_water)
    if not rows:
        raise FileFormatError(f"{path}: no atoms (no ATOM/HETATM records)")
    chain, resname, resseq, name = (np.array([r[i] for r in rows]) for i in range(4))
    centres = np.array([r[4:7] for r in rows], np.float64)
    radii = np.array([r[7] for r in rows], np.float64)
    residues = np.char.add(np.char.add(np.char.add(chain, ":"), np.char.add(resname, ":")),
                           resseq)
    return _finish(path, centres, radii, name, residues, waters, models,
                   chains=len(set(chain.tolist())))


def read_xyzr(path: Path, keep_water: bool = False) -> AtomTable:
    """The atoms of an XYZR file (MSMS: x y z radius [name] per line)."""
    del keep_water  # XYZR names no residues: nothing to recognise as water
    centres, radii, names = [], [], []
    with open(path, encoding="utf-8", errors="replace") as handle:
        for number, line in enumerate(handle, 1):
            f = line.split("#", 1)[0].split()
            if not f:
                continue
            try:
                x, y, z, r = map(float, f[:4])
            except ValueError:
                raise FileFormatError(f"{path}: line {number}: an XYZR line is x y z radius "
                                      "(numbers)") from None
            centres.append((x, y, z))
            radii.append(r)
            names.append(f[4] if len(f) > 4 else "")
    if not centres:
        raise FileFormatError(f"{path}: no atoms")
    centres_arr = np.array(centres, np.float64)
    residues = np.array([f"::{i + 1}" for i in range(len(radii))])
    return _finish(path, centres_arr, np.array(radii, np.float64), np.array(names),
                   residues, 0, 1, chains=0)


def _finish(path, centres, radii, names, residues, waters, models, chains) -> AtomTable:
    """The AtomTable, its radii checked (each > 0 and finite, else an error)."""
    bad = ~(np.isfinite(radii) & (radii > 0))
    if bad.any():
        raise FileFormatError(f"{path}: {int(bad.sum()):,} atoms with a radius that is not a "
                              f"positive number (first at atom {int(np.argmax(bad)) + 1})")
    if not np.all(np.isfinite(centres)):
        raise FileFormatError(f"{path}: non-finite atom coordinates")
    guessed = [_element_of(str(n)) for n in names]
    return AtomTable(centres, radii, np.array([g[0] for g in guessed]),
                     np.array([g[1] for g in guessed], np.int16), residues, names, waters,
                     models, chains)

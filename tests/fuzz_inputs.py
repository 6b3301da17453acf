"""Small valid files of every readable format, and deterministic mutations of them for the
fuzz tests (truncations, byte flips, wrong header counts, huge declared sizes, sparse and
endless inputs)."""

from __future__ import annotations

import re
from collections.abc import Callable, Iterator
from pathlib import Path

import numpy as np

DATA = Path(__file__).parent / "data"
E57_SAMPLE = DATA / "corpus" / "e57" / "pye57_translationWithoutRotation.e57"
E57_BOUNDED = DATA / "corpus" / "e57" / "libe57_ColourRepresentation.e57"  # 153 points
MOLECULE = DATA / "molecules" / "gemmi_4hhh_frag.pdb"  # alternate conformations A and B
LIGAND = DATA / "molecules" / "gemmi_HEM.pdb"
SPARSE_BYTES = 64 << 20  # apparent size of a sparse file (holes cost no disk)
ENDLESS_BYTES = 4 << 20  # junk appended without a line break


def _points() -> np.ndarray:
    return np.random.default_rng(0).normal(size=(30, 3)).astype(np.float32)


def _ply(path: Path, text: bool) -> None:
    import plyfile

    vert = np.rec.fromarrays(_points().T, names="x,y,z")
    faces = np.array([([0, 1, 2],), ([2, 3, 4],)], dtype=[("vertex_indices", "i4", (3,))])
    plyfile.PlyData([plyfile.PlyElement.describe(vert, "vertex"),
                     plyfile.PlyElement.describe(faces, "face")], text=text).write(str(path))


def _text(path: Path, sep: str, header: str) -> None:
    pts = _points()
    path.write_text(header + "".join(sep.join(f"{v:.6g}" for v in p) + "\n" for p in pts))


def _pcd(path: Path, encoding: str) -> None:
    from pypcd4 import Encoding, PointCloud

    PointCloud.from_xyz_points(_points()).save(path, encoding=Encoding(encoding))


def _las(path: Path) -> None:
    import laspy

    las = laspy.LasData(laspy.LasHeader(point_format=3, version="1.2"))
    las.x, las.y, las.z = _points().T.astype(np.float64)
    las.write(path)


def _trimesh(path: Path) -> None:
    import trimesh

    pts = _points()
    trimesh.Trimesh(pts, np.array([[0, 1, 2], [2, 3, 4]]), process=False).export(path)


def _meshio(path: Path) -> None:
    import meshio

    meshio.write(str(path), meshio.Mesh(_points(), [("triangle", np.array([[0, 1, 2]]))]),
                 **({"binary": False} if path.suffix == ".vtk" else {}))


def _mmcif(path: Path) -> None:
    """The 4HHH fragment as mmCIF (gemmi's writer)."""
    import gemmi

    structure = gemmi.read_structure(str(MOLECULE))
    structure.setup_entities()
    structure.make_mmcif_document().write_file(str(path))


def _weighted(path: Path) -> None:
    """x, y, z and a radius column: read as a weighted set (squared radii)."""
    radii = np.random.default_rng(1).uniform(0.05, 0.3, 30)
    rows = np.column_stack([_points(), radii])
    path.write_text("x,y,z,radius\n" + "".join(",".join(f"{v:.6g}" for v in row) + "\n"
                                             for row in rows))


def _geographic(path: Path) -> None:
    """lon, lat, ele rows of a small track near Paris (projected to metres when read)."""
    pts = _points().astype(np.float64)
    rows = np.column_stack([2.35 + 0.01 * pts[:, 0], 48.85 + 0.01 * pts[:, 1],
                            100.0 + 10.0 * pts[:, 2]])
    path.write_text("lon,lat,ele\n" + "".join(",".join(f"{v:.7f}" for v in row) + "\n"
                                            for row in rows))


MAKERS: dict[str, tuple[str, Callable[[Path], None]]] = {
    "ply-ascii": (".ply", lambda p: _ply(p, True)),
    "ply-binary": (".ply", lambda p: _ply(p, False)),
    "csv": (".csv", lambda p: _text(p, ",", "x,y,z\n")),
    "xyz": (".xyz", lambda p: _text(p, " ", "")),
    "pts": (".pts", lambda p: _text(p, " ", "30\n")),
    "txt": (".txt", lambda p: _text(p, "\t", "//X\tY\tZ\n")),
    "pcd-ascii": (".pcd", lambda p: _pcd(p, "ascii")),
    "pcd-binary": (".pcd", lambda p: _pcd(p, "binary")),
    "pcd-compressed": (".pcd", lambda p: _pcd(p, "binary_compressed")),
    "las": (".las", _las),
    "laz": (".laz", _las),
    "npy": (".npy", lambda p: np.save(p, _points())),
    "npz": (".npz", lambda p: np.savez_compressed(p, points=_points())),
    "obj": (".obj", _trimesh),
    "stl": (".stl", _trimesh),
    "off": (".off", _trimesh),
    "glb": (".glb", _trimesh),
    "gltf": (".gltf", _trimesh),
    "vtk": (".vtk", _meshio),
    "vtu": (".vtu", _meshio),
    "e57": (".e57", lambda p: p.write_bytes(E57_SAMPLE.read_bytes())),  # from the corpus
    "e57-bounded": (".e57", lambda p: p.write_bytes(E57_BOUNDED.read_bytes())),
    "pdb": (".pdb", lambda p: p.write_bytes(MOLECULE.read_bytes())),
    "pdb-ligand": (".pdb", lambda p: p.write_bytes(LIGAND.read_bytes())),
    "cif": (".cif", _mmcif),
    "weighted": (".csv", _weighted),
    "geographic": (".csv", _geographic),
}


def original(kind: str, folder: Path) -> Path:
    """A small valid file of this kind in `folder`."""
    ext, make = MAKERS[kind]
    path = folder / f"valid-{kind}{ext}"
    make(path)
    return path


def _numbers_in_head(raw: bytes) -> list[re.Match]:
    return list(re.finditer(rb"\d+", raw[:1024]))


def mutate(raw: bytes, how: str, rng: np.random.Generator) -> bytes | tuple[bytes, int]:
    """The mutated bytes; for 'sparse', (bytes, apparent size to extend the file to)."""
    at = int(rng.integers(0, max(len(raw), 1)))
    junk = rng.integers(0, 256, int(rng.integers(1, 13)), dtype=np.uint8).tobytes()
    if how == "cut":
        return raw[:at]
    if how == "flip":
        return raw[:at] + junk[: len(raw) - at] + raw[at + len(junk):]
    if how == "insert":
        return raw[:at] + junk + raw[at:]
    if how == "header-count":  # a number in the header made huge, zero or negative
        found = _numbers_in_head(raw)
        if not found:
            return raw
        m = found[int(rng.integers(0, len(found)))]
        new = [b"99999999999", b"0", b"-1", b"4294967295", b"1" + m.group()][
            int(rng.integers(0, 5))]
        return raw[:m.start()] + new + raw[m.end():]
    if how == "header-int":  # a binary size field made huge
        at = int(rng.integers(0, min(len(raw), 256) - 3))
        value = [b"\xff\xff\xff\xff", b"\xff\xff\xff\x7f", b"\x00\x00\x00\x80"][
            int(rng.integers(0, 3))]
        return raw[:at] + value + raw[at + 4:]
    if how == "sparse":
        return raw, SPARSE_BYTES
    if how == "endless":
        return raw[: len(raw) // 2] + bytes([int(rng.integers(33, 127))]) * ENDLESS_BYTES
    raise ValueError(how)


MUTATIONS = ("cut", "flip", "insert", "header-count", "header-int", "sparse", "endless")


def cases(kinds, per_kind: int, seed: int) -> Iterator[tuple[str, str, int]]:
    """(kind, mutation, case seed), round-robin over kinds so any prefix covers them all."""
    for i in range(per_kind):
        for j, kind in enumerate(kinds):
            yield kind, MUTATIONS[(i + j) % len(MUTATIONS)], seed + 1000 * i + j


def write_case(raw: bytes, ext: str, how: str, case_seed: int, folder: Path) -> Path:
    """Write the mutated file; sparse ones are extended with a hole (no disk used)."""
    out = mutate(raw, how, np.random.default_rng(case_seed))
    path = folder / f"fuzz-{case_seed}{ext}"
    data, size = out if isinstance(out, tuple) else (out, None)
    path.write_bytes(data)
    if size is not None:
        with open(path, "r+b") as fh:
            fh.truncate(size)
    return path

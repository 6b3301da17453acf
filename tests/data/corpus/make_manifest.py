"""Write MANIFEST.json: per corpus file, its point records, bounding box and attributes as
INDEPENDENT readers see them (plyfile, laspy, pye57's own read_scan, pygltflib, VTK, and small
numpy parsers written here from the format specifications); never the project's readers.

Run once when the corpus changes: python tests/data/corpus/make_manifest.py
"""

from __future__ import annotations

import json
import re
import struct
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
PCD_TYPES = {("F", 4): "f4", ("F", 8): "f8", ("U", 1): "u1", ("U", 2): "u2", ("U", 4): "u4",
             ("I", 1): "i1", ("I", 2): "i2", ("I", 4): "i4", ("U", 8): "u8", ("I", 8): "i8"}
# Text files: how numpy.loadtxt is told to read each one (columns chosen by hand).
TEXT = {
    "pdal_autzen_point_format_3.txt": {"delimiter": ",", "skiprows": 1, "usecols": (2, 3, 5),
                                       "attributes": ["colors"]},
    "pdal_bunny_8.pts": {"skiprows": 1, "usecols": (0, 1, 2)},
    "pdal_test.pts": {"skiprows": 1, "usecols": (0, 1, 2)},
    "pdal_gdal_data.xyz": {"usecols": (0, 1, 2)},
    "trimesh_points_agisoft.xyz": {"usecols": (0, 1, 2)},
    "trimesh_points_cloudcompare.xyz": {"usecols": (0, 1, 2)},
}


def _entry(xyz: np.ndarray, attributes: list[str]) -> dict:
    xyz = np.asarray(xyz, dtype=np.float64)
    finite = xyz[np.all(np.isfinite(xyz), axis=1)]
    return {"points": len(xyz), "bbox": [finite.min(axis=0).tolist(), finite.max(axis=0).tolist()],
            "attributes": sorted(attributes)}


def ply(path: Path) -> dict:
    import plyfile

    vertex = plyfile.PlyData.read(str(path))["vertex"]
    names = [p.name for p in vertex.properties if not isinstance(p, plyfile.PlyListProperty)]
    attrs, rest = [], set(names) - {"x", "y", "z"}
    if {"nx", "ny", "nz"} <= rest:
        attrs.append("normals")
        rest -= {"nx", "ny", "nz"}
    for triple in (("red", "green", "blue"), ("r", "g", "b")):
        if set(triple) <= rest:
            attrs.append("colors")
            rest -= set(triple)
    return _entry(np.column_stack([vertex[a] for a in "xyz"]), attrs + sorted(rest))


def pcd(path: Path) -> dict:
    """ascii and binary PCD by the PCL specification (no compressed files in the corpus)."""
    data = path.read_bytes()
    header, pos = {}, 0
    while True:
        end = data.index(b"\n", pos)
        words = data[pos:end].decode().split()
        pos = end + 1
        if words and not words[0].startswith("#"):
            header[words[0].upper()] = words[1:]
            if words[0].upper() == "DATA":
                break
    names = [n.lower() for n in header["FIELDS"]]
    counts = [int(c) for c in header.get("COUNT", ["1"] * len(names))]
    n = int(header["POINTS"][0])
    if header["DATA"][0] == "ascii":
        table = np.loadtxt(data[pos:].decode().splitlines(), ndmin=2)[:n]
        at = np.cumsum([0, *counts])[:-1]
        cols = {name: table[:, a].astype(PCD_TYPES[(t, int(size))])  # the declared type
                for name, a, t, size in zip(names, at, header["TYPE"], header["SIZE"],
                                            strict=True)}
    else:
        dtype = np.dtype([(name, PCD_TYPES[(t, int(s))], (c,)) for name, t, s, c in
                          zip(names, header["TYPE"], header["SIZE"], counts, strict=True)])
        rows = np.frombuffer(data, dtype=dtype, count=n, offset=pos)
        cols = {name: rows[name][:, 0] for name in names}
    attrs = [a for a, need in (("normals", "normal_x"), ("colors", "rgb"),
                               ("intensity", "intensity")) if need in cols]
    return _entry(np.column_stack([cols["x"], cols["y"], cols["z"]]), attrs)


def las(path: Path) -> dict:
    import laspy

    data = laspy.read(str(path))
    dims = set(data.point_format.dimension_names)
    colours = "red" in dims and any(np.any(data[c]) for c in ("red", "green", "blue"))
    attrs = ["intensity", "classification"] + (["colors"] if colours else [])  # 0s: no colour
    return _entry(np.column_stack([data.x, data.y, data.z]), attrs)


def obj(path: Path) -> dict:
    rows = re.findall(rb"^\s*v\s+([^\n#]*)", path.read_bytes(), re.M)
    table = np.array([r.split()[:3] for r in rows], dtype=np.float64)
    colours = all(len(r.split()) in (6, 7) for r in rows)
    return _entry(table, ["colors"] if colours else [])


def stl(path: Path) -> dict:
    data = path.read_bytes()
    n = struct.unpack("<I", data[80:84])[0]
    if 84 + 50 * n == len(data):
        rows = np.frombuffer(data, dtype=[("n", "<f4", 3), ("v", "<f4", (3, 3)), ("a", "<u2")],
                             count=n, offset=84)
        return _entry(rows["v"].reshape(-1, 3), [])
    found = re.findall(rb"vertex\s+(\S+)\s+(\S+)\s+(\S+)", data)
    return _entry(np.array(found, dtype=np.float64), [])


def off(path: Path) -> dict:
    lines = [ln.split("#")[0].split() for ln in path.read_text().splitlines()]
    lines = [ln for ln in lines if ln]
    first = [lines[0][0].removeprefix("OFF"), *lines[0][1:]]  # 'OFF8 6 12' happens
    words = [w for w in first if w]
    if not words:
        lines, words = lines[1:], lines[1]
    nv = int(words[0])
    return _entry(np.array([ln[:3] for ln in lines[1 : 1 + nv]], dtype=np.float64), [])


def _node_matrix(node) -> np.ndarray:
    """4x4 local transform of a glTF node (column-major matrix or TRS)."""
    if node.matrix:
        return np.array(node.matrix, dtype=np.float64).reshape(4, 4).T
    t, (x, y, z, w), s = node.translation or [0, 0, 0], node.rotation or [0, 0, 0, 1], \
        node.scale or [1, 1, 1]
    r = np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                  [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                  [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])
    m = np.eye(4)
    m[:3, :3], m[:3, 3] = r * np.asarray(s), t
    return m


def gltf(path: Path) -> dict:
    import pygltflib

    doc = pygltflib.GLTF2().load(str(path))
    blob = doc.binary_blob() if path.suffix == ".glb" else (
        path.parent / doc.buffers[0].uri).read_bytes()
    points, colours = [], []

    def positions(index: int) -> np.ndarray:
        acc = doc.accessors[index]
        view = doc.bufferViews[acc.bufferView]
        offset = (view.byteOffset or 0) + (acc.byteOffset or 0)
        stride = view.byteStride or 12
        raw = np.frombuffer(blob, dtype=np.uint8, count=stride * (acc.count - 1) + 12,
                            offset=offset)
        idx = np.arange(acc.count)[:, None] * stride + np.arange(12)
        return raw[idx].reshape(-1).view("<f4").reshape(-1, 3).astype(np.float64)

    def walk(i: int, parent: np.ndarray) -> None:
        node = doc.nodes[i]
        m = parent @ _node_matrix(node)
        if node.mesh is not None:
            for prim in doc.meshes[node.mesh].primitives:
                p = positions(prim.attributes.POSITION)
                points.append(p @ m[:3, :3].T + m[:3, 3])
                colours.append(prim.attributes.COLOR_0 is not None)
        for child in node.children or []:
            walk(child, m)

    for root in doc.scenes[doc.scene or 0].nodes:
        walk(root, np.eye(4))
    return _entry(np.vstack(points), ["colors"] if all(colours) else [])


def e57(path: Path) -> dict:
    import pye57

    with pye57.E57(str(path)) as f:
        scans = [f.read_scan(i, ignore_missing_fields=True) for i in range(f.scan_count)]
        fields = [set(f.get_header(i).point_fields) for i in range(f.scan_count)]
    xyz = np.vstack([np.column_stack([s["cartesianX"], s["cartesianY"], s["cartesianZ"]])
                     for s in scans])
    attrs = [a for a, key in (("intensity", "intensity"), ("colors", "colorRed"))
             if all(key in f for f in fields)]
    return _entry(xyz, attrs)


def vtk(path: Path) -> dict:
    """VTK's own legacy reader (through pyvista)."""
    import pyvista

    return _entry(np.asarray(pyvista.read(path).points), [])


def text(path: Path) -> dict:
    options = dict(TEXT[path.name])
    attrs = options.pop("attributes", [])
    return _entry(np.loadtxt(path, ndmin=2, **options), attrs)


READERS = {".ply": ply, ".pcd": pcd, ".las": las, ".laz": las, ".obj": obj, ".stl": stl,
           ".off": off, ".glb": gltf, ".gltf": gltf, ".e57": e57, ".vtk": vtk, ".pts": text,
           ".xyz": text, ".txt": text}


def main() -> None:
    manifest = {}
    for path in sorted(HERE.rglob("*")):
        if path.suffix.lower() in READERS:
            manifest[str(path.relative_to(HERE))] = READERS[path.suffix.lower()](path)
    (HERE / "MANIFEST.json").write_text(json.dumps(manifest, indent=1) + "\n")


if __name__ == "__main__":
    main()

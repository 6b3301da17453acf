"""Bad point files fail with one exception type naming the file, never a hang or a deep trace."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from core.errors import FileFormatError
from core.io import read_points

PLY_HEAD = "ply\nformat {fmt} 1.0\nelement vertex {n}\nproperty float x\nproperty float y\n" \
           "property float z\nend_header\n"


def _write(tmp_path: Path, name: str, content: bytes | str) -> Path:
    """Write a small file and return its path."""
    path = tmp_path / name
    path.write_bytes(content.encode() if isinstance(content, str) else content)
    return path


BAD_FILES = {
    "empty.ply": b"",
    "empty.csv": b"",
    "blank.xyz": "\n\n  \n",
    "only_header.csv": "x,y,z\n",
    "comments.xyz": "# nothing\n# here\n",
    "wrong_magic.ply": "plx\nformat ascii 1.0\nend_header\n",
    "bad_format.ply": "ply\nformat weird 1.0\nelement vertex 1\nproperty float x\nend_header\n",
    "no_vertex.ply": "ply\nformat ascii 1.0\nelement face 0\n"
                     "property list uchar int vertex_indices\nend_header\n",
    "no_xy.ply": "ply\nformat ascii 1.0\nelement vertex 1\nproperty float q\nend_header\n1\n",
    "trunc_ascii.ply": PLY_HEAD.format(fmt="ascii", n=5) + "0 0 0\n1 1 1\n",
    "trunc_binary.ply": PLY_HEAD.format(fmt="binary_little_endian", n=5).encode()
                        + np.zeros((2, 3), "<f4").tobytes(),
    "bogus_count.ply": PLY_HEAD.format(fmt="binary_little_endian", n=10**15).encode()
                       + b"\0" * 24,
    "bogus_count_ascii.ply": PLY_HEAD.format(fmt="ascii", n=10**15) + "0 0 0\n",
    "text_in_ply.ply": PLY_HEAD.format(fmt="ascii", n=2) + "0 0 0\n1 a 1\n",
    "non_numeric.csv": "x,y,z\n1,2,3\n4,five,6\n",
    "non_numeric.xyz": "1 2 3\n4 5 6\nseven 8 9\n",
    "one_column.txt": "1\n2\n3\n",
    "ragged.xyz": "1 2 3\n4 5\n",
    "binary.xyz": b"\x00\x01\x02\x03" * 100,
    "all_nan.xyz": "nan nan nan\nnan 1 2\n",
    "garbage.npy": b"not numpy at all",
    "broken.npz": b"PK\x03\x04 broken zip",
    "pickled.npy": b"\x93NUMPY\x01\x00v\x00{'descr': '|O', 'fortran_order': False, "
                   b"'shape': (1,), }" + b" " * 60 + b"\n" + b"\x80\x04N.",
    "garbage.pcd": "# .PCD v0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\n"
                   "WIDTH 1000000\nHEIGHT 1\nPOINTS 1000000\nDATA binary\n" + "x" * 30,
    "bogus_count.pcd": "# .PCD v0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\n"
                       "WIDTH 1000000000000\nHEIGHT 1\nPOINTS 1000000000000\n"
                       "DATA binary_compressed\n" + "\x10\0\0\0\x20\0\0\0" + "x" * 16,
    "garbage.las": b"LASF" + b"\0" * 300,
    "garbage.laz": b"not a laz file" * 10,
    "garbage.stl": b"solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0\n",
    "garbage.vtu": "<VTKFile><broken",
    "unknown.foo": "1 2 3\n",
    "noext": "1 2 3\n",
}


@pytest.mark.parametrize("name", sorted(BAD_FILES))
def test_bad_file_raises_format_error_naming_file(tmp_path, name):
    path = _write(tmp_path, name, BAD_FILES[name])
    with pytest.raises(FileFormatError) as info:
        read_points(path)
    assert name in str(info.value)
    assert len(str(info.value).splitlines()) == 1


def test_missing_file(tmp_path):
    with pytest.raises(FileFormatError, match="no such file"):
        read_points(tmp_path / "absent.ply")


def test_unknown_extension_lists_known(tmp_path):
    path = _write(tmp_path, "points.dat", "1 2 3\n")
    with pytest.raises(FileFormatError, match=r"unknown extension '\.dat'.*\.ply"):
        read_points(path)


def test_non_numeric_message_gives_line_and_column(tmp_path):
    path = _write(tmp_path, "p.csv", "x,y\n1,2\n3,4\n5,oops\n")
    with pytest.raises(FileFormatError, match=r"'oops' at line 4, column 2"):
        read_points(path)


def test_truncated_ply_message(tmp_path):
    path = _write(tmp_path, "t.ply", BAD_FILES["trunc_binary.ply"])
    with pytest.raises(FileFormatError, match="truncated"):
        read_points(path)


@pytest.mark.parametrize("ext", ["las", "laz"])
def test_las_bogus_point_count_and_truncation(tmp_path, ext):
    import struct

    import laspy

    las = laspy.LasData(laspy.LasHeader(point_format=3, version="1.2"))
    las.x, las.y, las.z = np.random.default_rng(0).uniform(size=(3, 10))
    las.write(tmp_path / f"ok.{ext}")
    raw = bytearray((tmp_path / f"ok.{ext}").read_bytes())
    (tmp_path / f"cut.{ext}").write_bytes(raw[:-60])
    raw[107:111] = struct.pack("<I", 4_000_000_000)  # legacy point count in the header
    (tmp_path / f"huge.{ext}").write_bytes(raw)
    with pytest.raises(FileFormatError, match="truncated"):
        read_points(tmp_path / f"huge.{ext}")
    with pytest.raises(FileFormatError, match=f"cut.{ext}"):
        read_points(tmp_path / f"cut.{ext}")


@pytest.fixture
def laz_bytes(tmp_path) -> bytearray:
    """A small valid LAZ file's bytes."""
    import laspy

    las = laspy.LasData(laspy.LasHeader(point_format=3, version="1.2"))
    las.x, las.y, las.z = np.random.default_rng(1).uniform(size=(3, 30))
    las.write(tmp_path / "ok.laz")
    return bytearray((tmp_path / "ok.laz").read_bytes())


def test_corrupt_vlr_count_does_not_hang(tmp_path, laz_bytes):
    import struct

    laz_bytes[100:104] = struct.pack("<I", 3_000_000_000)  # number of VLRs
    (tmp_path / "vlr.laz").write_bytes(laz_bytes)
    with pytest.raises(FileFormatError, match="corrupt LAS header"):
        read_points(tmp_path / "vlr.laz")


def test_corrupt_chunk_table_does_not_abort(tmp_path, laz_bytes):
    import struct

    offset = struct.unpack_from("<I", laz_bytes, 96)[0]
    table = struct.unpack_from("<q", laz_bytes, offset)[0]
    laz_bytes[table + 4: table + 8] = struct.pack("<I", 833_707_467)  # number of chunks
    (tmp_path / "chunks.laz").write_bytes(laz_bytes)
    with pytest.raises(FileFormatError, match="chunk table"):
        read_points(tmp_path / "chunks.laz")

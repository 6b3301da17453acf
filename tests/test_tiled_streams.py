"""Text and PLY files streamed in chunks for tiled runs give exactly the points a whole read
gives, and a tiled run on them equals the in-memory answer without reading them whole."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from core.errors import FileFormatError
from core.io import streams
from core.io.ply import read_ply
from core.io.streams import PlySource, TextSource, streamed_source
from core.io.text import read_text
from tests.tiled_reference import same_info

SHARED = Path(__file__).resolve().parents[2] / "shared" / "data"
SHARED = SHARED if SHARED.is_dir() else Path("/work/shared/data")


def streamed(source) -> np.ndarray:
    parts = [coords for coords, weights in source.chunks() if weights is None]
    return np.concatenate(parts) if parts else np.empty((0, source.dim))


def finite(points: np.ndarray) -> np.ndarray:
    return points[np.isfinite(points).all(axis=1)]


def cloud(n: int = 101, dim: int = 3) -> np.ndarray:
    return np.random.default_rng(5).normal(size=(n, dim)) * 1e3


TEXTS = {
    "plain.xyz": lambda p: "\n".join(" ".join(repr(v) for v in row) for row in p),
    "header.csv": lambda p: "x,y,z,intensity\n" + "\n".join(
        f"{a!r},{b!r},{c!r},7" for a, b, c in p),
    "comments.txt": lambda p: "# a scan\n" + "\n".join(
        ("# midway\n\n" if i % 13 == 0 else "") + f"{a!r}\t{b!r}\t{c!r}"
        for i, (a, b, c) in enumerate(p)),
    "gaps.csv": lambda p: "x;y;z\n" + "\n".join(
        f"{a!r};{'' if i % 17 == 5 else repr(b)};{c!r}" for i, (a, b, c) in enumerate(p)),
    "scans.pts": lambda p: "50\n" + "\n".join(f"{a!r} {b!r} {c!r}" for a, b, c in p[:50])
    + "\n51\n" + "\n".join(f"{a!r} {b!r} {c!r}" for a, b, c in p[50:]),
    "comma.xyz": lambda p: "\n".join(
        " ".join(f"{v:.6f}".replace(".", ",") for v in row) for row in p),
}


@pytest.mark.parametrize("name", sorted(TEXTS))
def test_text_chunks_equal_the_whole_read(tmp_path, name):
    path = tmp_path / name
    path.write_text(TEXTS[name](cloud().tolist()) + "\n")
    whole = finite(read_text(path)[0])
    source = TextSource.open(path, chunk=7)
    assert source is not None and source.dim == 3
    parts = streamed(source)
    assert parts.shape == whole.shape and parts.tobytes() == whole.tobytes()


def test_text_2d_and_a_bad_value_named_alike(tmp_path):
    path = tmp_path / "survey.csv"
    rows = [f"{a!r},{b!r}" for a, b in cloud(40, 2).tolist()]
    path.write_text("easting,northing\n" + "\n".join(rows) + "\n")
    assert streamed(TextSource.open(path, chunk=6)).tobytes() == read_text(path)[0].tobytes()
    rows[29] = "1.5,oops"
    path.write_text("easting,northing\n" + "\n".join(rows) + "\n")
    with pytest.raises(FileFormatError) as whole:
        read_text(path)
    with pytest.raises(FileFormatError) as parts:
        streamed(TextSource.open(path, chunk=6))
    assert str(parts.value) == str(whole.value)
    assert "line 31" in str(parts.value)


def write_ply(path: Path, points: np.ndarray, fmt: str, dtype: str = "f8",
              faces: int = 0) -> None:
    """A PLY of `points` (float `dtype`), with `faces` triangles after the vertices."""
    kind = {"f4": "float", "f8": "double"}[dtype]
    names = "xyz"[: points.shape[1]]
    head = [f"ply\nformat {fmt} 1.0\nelement vertex {len(points)}"]
    head += [f"property {kind} {a}" for a in names] + ["property uchar red"]
    head += [f"element face {faces}\nproperty list uchar int vertex_indices\nend_header\n"]
    with open(path, "wb") as fh:
        fh.write("\n".join(head).encode())
        if fmt == "ascii":
            for row in points:
                fh.write((" ".join(repr(float(v)) for v in row) + " 200\n").encode())
            for f in range(faces):
                fh.write(f"3 {f} {f + 1} {f + 2}\n".encode())
            return
        order = "<" if fmt == "binary_little_endian" else ">"
        table = np.empty(len(points), [(a, order + dtype) for a in names] + [("red", "u1")])
        for i, a in enumerate(names):
            table[a] = points[:, i]
        table["red"] = 200
        fh.write(table.tobytes())
        tri = np.empty(faces, [("n", "u1"), ("v", order + "i4", (3,))])
        tri["n"], tri["v"] = 3, np.arange(faces)[:, None] + np.arange(3)
        fh.write(tri.tobytes())


@pytest.mark.parametrize("fmt", ["binary_little_endian", "binary_big_endian", "ascii"])
@pytest.mark.parametrize("dtype", ["f4", "f8"])
def test_ply_chunks_equal_the_whole_read(tmp_path, fmt, dtype):
    points = cloud()
    points[[3, 60]] = np.nan
    path = tmp_path / "scan.ply"
    write_ply(path, points, fmt, dtype, faces=5)
    whole = finite(read_ply(path)[0])
    parts = streamed(PlySource.open(path, chunk=8))
    assert parts.dtype == np.float64 and parts.tobytes() == whole.tobytes()
    assert len(parts) == len(points) - 2


def test_ply_2d_and_truncated(tmp_path):
    path = tmp_path / "flat.ply"
    write_ply(path, cloud(30, 2), "binary_little_endian")
    assert streamed(PlySource.open(path, chunk=4)).tobytes() == read_ply(path)[0].tobytes()
    path = tmp_path / "cut.ply"
    write_ply(path, cloud(300), "binary_little_endian")
    source = PlySource.open(path, chunk=64)
    data = path.read_bytes()
    path.write_bytes(data[: len(data) - 1000])  # cut after the header was checked
    with pytest.raises(FileFormatError, match="truncated PLY"):
        streamed(source)


def test_what_is_not_streamed(tmp_path):
    """Files a whole read would change (weights, longitude/latitude, list properties) and
    small files are read whole: streamed_source says None."""
    lonlat = tmp_path / "stations.csv"
    lonlat.write_text("lon,lat\n" + "\n".join(f"{10 + a / 1e4!r},{45 + b / 1e4!r}"
                                              for a, b in cloud(20, 2).tolist()) + "\n")
    radii = tmp_path / "balls.xyz"
    radii.write_text("x y z radius\n" + "\n".join(f"{a!r} {b!r} {c!r} 1.5"
                                                  for a, b, c in cloud(20).tolist()) + "\n")
    plain = tmp_path / "plain.xyz"
    plain.write_text(TEXTS["plain.xyz"](cloud(20).tolist()) + "\n")
    listed = tmp_path / "listed.ply"
    listed.write_text("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n"
                      "property float y\nproperty list uchar int ids\nend_header\n1 2 0\n")
    for path in (lonlat, radii, listed):
        assert streamed_source(path, stream_from=0) is None, path.name
    assert isinstance(streamed_source(plain, stream_from=0), TextSource)
    assert streamed_source(plain, stream_from=plain.stat().st_size + 1) is None
    assert streamed_source(tmp_path / "absent.xyz", stream_from=0) is None


@pytest.mark.parametrize("kind", ["ply", "xyz"])
def test_tiled_info_on_a_streamed_scan_equals_in_memory(tmp_path, capsys, monkeypatch, kind):
    """`info --tiled` on a real scan as binary PLY and as text equals the in-memory `info`,
    and the tiled run never reads the file whole."""
    pytest.importorskip("distributed")
    import core.io
    from app.cli import main
    from core.io import read_points

    bunny = SHARED / "bunny.ply"
    if not bunny.exists():
        pytest.skip(f"{bunny} is not here")
    points = read_points(bunny).points
    points = points[points[:, 0] <= np.quantile(points[:, 0], 0.4)]
    path = tmp_path / f"piece.{kind}"
    if kind == "ply":
        write_ply(path, points, "binary_little_endian", "f4")
    else:
        path.write_text("\n".join(" ".join(repr(float(v)) for v in p) for p in points) + "\n")
    argv = ["info", str(path), "--alpha", "0.003", "--json"]
    assert main(argv) == 0
    memory = json.loads(capsys.readouterr().out)

    def whole_read(*args, **kwargs):
        raise AssertionError("a streamed file was read whole")

    monkeypatch.setattr(streams, "STREAM_FROM_BYTES", 0)
    monkeypatch.setattr(core.io, "read_points", whole_read)
    assert main([*argv, "--tiled", "--tile-points", "2000", "--memory-per-worker",
                 "1GiB"]) == 0, capsys.readouterr().err
    tiled = json.loads(capsys.readouterr().out)
    assert tiled["tiles"] >= 4
    assert same_info(tiled, memory) == []


def test_ascii_ply_blank_and_comment_lines_among_vertices(tmp_path):
    """np.loadtxt, reading a whole ASCII vertex element, passes over blank and '#' lines
    without counting them as vertices; the streamed rows do the same, after an element
    before the vertices."""
    path = tmp_path / "gaps.ply"
    path.write_text("ply\nformat ascii 1.0\nelement camera 2\nproperty float f\n"
                    "element vertex 5\nproperty double x\nproperty double y\n"
                    "property double z\nend_header\n1.5\n2.5\n\n0 0 0\n1 0 0\n# a note\n"
                    "0 1 0\n\n0 0 1\n1 1 1\n")
    from core.io import read_points

    whole = read_points(path).points
    assert len(whole) == 5
    for chunk in (1, 2, 8):
        assert streamed(PlySource.open(path, chunk=chunk)).tobytes() == whole.tobytes()



def test_ply_radius_property_is_not_streamed(tmp_path):
    """A whole read squares a PLY 'radius' property into weights: such a file is read whole,
    never streamed as plain points."""
    from core.io import read_points

    path = tmp_path / "balls.ply"
    path.write_text("ply\nformat ascii 1.0\nelement vertex 3\nproperty double x\n"
                    "property double y\nproperty double radius\nend_header\n"
                    "0 0 1\n1 0 2\n0 1 3\n")
    assert read_points(path).weights.tolist() == [1.0, 4.0, 9.0]
    assert streamed_source(path, stream_from=0) is None


def error_alike(path: Path, chunk: int) -> str:
    """The streamed read's error on `path`, which must be the whole read's, word for word."""
    from core.io import read_points

    with pytest.raises(FileFormatError) as whole:
        read_points(path)
    with pytest.raises(FileFormatError) as parts:
        streamed(streamed_source(path, stream_from=0, chunk=chunk))
    assert str(parts.value) == str(whole.value)
    return str(parts.value)


@pytest.mark.parametrize("kind", ["xyz", "ply"])
def test_too_large_coordinate_refused_as_the_whole_read_does(tmp_path, kind):
    """A coordinate beyond what an alpha shape can measure is the whole read's one-line
    error, naming the same point, not a later failure of the tiled run."""
    points = cloud(60)
    points[10, 0], points[41, 1] = np.nan, 1e200
    path = tmp_path / f"huge.{kind}"
    if kind == "ply":
        write_ply(path, points, "binary_little_endian")
    else:
        path.write_text("\n".join(" ".join(repr(v) for v in p) for p in points.tolist())
                        + "\n")
    assert "point 42" in error_alike(path, chunk=8)


@pytest.mark.parametrize("kind", ["xyz", "ply"])
def test_nul_bytes_refused_before_streaming(tmp_path, kind):
    """A text file (or ASCII PLY) whose tail is NUL bytes (damaged, or sparse: its holes
    would be one endless line) is refused with the whole read's error before any chunk."""
    path = tmp_path / f"holes.{kind}"
    if kind == "ply":
        write_ply(path, cloud(2000), "ascii")
    else:
        path.write_text(TEXTS["plain.xyz"](cloud(2000).tolist()) + "\n")
    with open(path, "ab") as fh:
        fh.write(bytes(1 << 20))
    assert "NUL" in error_alike(path, chunk=64)


@pytest.mark.parametrize("head", [
    "element point 1\nproperty float x\nproperty float y\n",
    "element vertex 1\nproperty float u\nproperty float v\n",
], ids=["no vertex", "no x/y"])
def test_ply_without_vertex_axes_says_it_as_the_whole_read(tmp_path, head):
    from core.io import read_points

    path = tmp_path / "odd.ply"
    path.write_text(f"ply\nformat ascii 1.0\n{head}end_header\n1 2\n")
    with pytest.raises(FileFormatError) as whole:
        read_points(path)
    with pytest.raises(FileFormatError) as parts:
        streamed(streamed_source(path, stream_from=0))
    assert str(parts.value) == str(whole.value)


def test_ply_rewritten_without_vertices_is_a_format_error(tmp_path):
    """A PLY rewritten between opening its source and reading it (no vertex element any
    more) is the whole read's one-line format error, not a failure inside the stream."""
    path = tmp_path / "scan.ply"
    write_ply(path, cloud(50), "binary_little_endian")
    source = PlySource.open(path)
    path.write_text("ply\nformat ascii 1.0\nelement face 0\n"
                    "property list uchar int vertex_indices\nend_header\n")
    with pytest.raises(FileFormatError, match="no 'vertex' element"):
        streamed(source)

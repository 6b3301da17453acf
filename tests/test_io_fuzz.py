"""Corrupted files (truncated, bytes flipped or inserted) give FileFormatError or points, never
another exception. Regressions from fuzzing: a laspy loop and lazrs aborts (see las_checks)."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from core.errors import FileFormatError
from core.io import read_points

FORMATS = ("ply-ascii", "ply-binary", "csv", "xyz", "pcd", "pcd-compressed", "las", "laz",
           "stl", "obj", "off", "vtu", "npy", "npz")


def _write(kind: str, path_base) -> bytes:
    """Bytes of a small valid file of this kind."""
    pts = np.random.default_rng(0).normal(size=(30, 3)).astype(np.float32)
    ext = {"ply-ascii": "ply", "ply-binary": "ply", "pcd-compressed": "pcd"}.get(kind, kind)
    path = path_base.with_suffix("." + ext)
    if kind.startswith("ply"):
        import plyfile

        vert = np.rec.fromarrays(pts.T, names="x,y,z")
        plyfile.PlyData([plyfile.PlyElement.describe(vert, "vertex")],
                        text=kind == "ply-ascii").write(str(path))
    elif kind in ("csv", "xyz"):
        np.savetxt(path, pts, delimiter="," if kind == "csv" else " ",
                   header="x,y,z" if kind == "csv" else "", comments="")
    elif kind.startswith("pcd"):
        from pypcd4 import Encoding, PointCloud

        enc = Encoding("binary_compressed" if kind == "pcd-compressed" else "binary")
        PointCloud.from_xyz_points(pts).save(path, encoding=enc)
    elif kind in ("las", "laz"):
        import laspy

        las = laspy.LasData(laspy.LasHeader(point_format=3, version="1.2"))
        las.x, las.y, las.z = pts.T.astype(np.float64)
        las.write(path)
    elif kind in ("npy", "npz"):
        (np.save if kind == "npy" else lambda p, a: np.savez(p, points=a))(path, pts)
    else:
        import meshio

        meshio.write(str(path), meshio.Mesh(pts, [("triangle", np.array([[0, 1, 2]]))]))
    return path.read_bytes()


@pytest.fixture(scope="module")
def originals(tmp_path_factory) -> dict[str, bytes]:
    """Valid bytes per format."""
    base = tmp_path_factory.mktemp("orig") / "p"
    return {kind: _write(kind, base) for kind in FORMATS}


@settings(max_examples=120, deadline=None, derandomize=True,
          suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(kind=st.sampled_from(FORMATS), how=st.sampled_from(["cut", "flip", "insert"]),
       where=st.floats(0, 1), junk=st.binary(min_size=1, max_size=12))
def test_corrupt_file_gives_format_error_or_points(tmp_path, originals, kind, how, where, junk):
    raw = bytearray(originals[kind])
    at = int(where * (len(raw) - 1))
    if how == "cut":
        raw = raw[:at]
    elif how == "flip":
        raw[at: at + len(junk)] = junk[: len(raw) - at]
    else:
        raw[at:at] = junk
    ext = {"ply-ascii": "ply", "ply-binary": "ply", "pcd-compressed": "pcd"}.get(kind, kind)
    path = tmp_path / f"corrupt.{ext}"
    path.write_bytes(bytes(raw))
    try:
        ps = read_points(path)
    except FileFormatError as exc:
        assert "corrupt." in str(exc)
    else:
        assert ps.points.ndim == 2 and np.isfinite(ps.points).all()


# --- every reader, deterministic mutations, memory measured; and `alphascoop info` -----------

import re  # noqa: E402
import time  # noqa: E402
import tracemalloc  # noqa: E402
import warnings  # noqa: E402

from fuzz_inputs import MAKERS, MUTATIONS, cases, original, write_case  # noqa: E402

from app.cli import main  # noqa: E402

SEED = 17
READ_CASES_PER_KIND = 35  # 7 mutations five times over, for each of the 27 kinds
CLI_CASES_PER_KIND = 10
BUDGET_S = 20.0  # CPU seconds per test: cases past it are not run (each case is seeded), but
# a test that ran out before every kind met every mutation (or, for `info`, every kind once)
# fails: a slow reader cannot shrink the fuzzing unnoticed
PEAK_BASE = 32 << 20  # bytes a reader may use beyond twice the file's size
NOT_PLAIN = re.compile(r"Traceback|codec|Errno|please report|unexpected|\b\w+(Error|Exception)\b"
                       r"|\(\w+: |dtype|ndarray|usecols")


@pytest.fixture(scope="module")
def valid_bytes(tmp_path_factory) -> dict[str, bytes]:
    """Valid bytes of every kind; each must read as it is."""
    folder = tmp_path_factory.mktemp("valid")
    out = {}
    for kind in MAKERS:
        path = original(kind, folder)
        assert len(read_points(path).points) >= 4, kind
        out[kind] = path.read_bytes()
    return out


def assert_plain(message: str, path) -> None:
    """One line naming the file, saying the problem in words (no library jargon)."""
    assert message.startswith(f"{path}: ") and "\n" not in message, message
    assert not NOT_PLAIN.search(message[len(str(path)):]), message


@pytest.mark.timeout(120)
def test_every_reader_fuzzed(tmp_path, valid_bytes):
    deadline = time.process_time() + BUDGET_S
    tracemalloc.start()
    ran = 0
    try:
        for kind, how, seed in cases(list(MAKERS), READ_CASES_PER_KIND, SEED):
            if time.process_time() > deadline:
                break
            ran += 1
            path = write_case(valid_bytes[kind], MAKERS[kind][0], how, seed, tmp_path)
            tracemalloc.reset_peak()
            with warnings.catch_warnings(record=True) as caught:
                warnings.simplefilter("always")
                try:
                    ps = read_points(path)
                except FileFormatError as exc:
                    assert_plain(str(exc), path)
                else:
                    assert ps.points.ndim == 2 and np.isfinite(ps.points).all()
            peak = tracemalloc.get_traced_memory()[1]
            assert peak < PEAK_BASE + 2 * path.stat().st_size, (kind, how, seed, peak)
            assert not caught, (kind, how, seed, [str(w.message) for w in caught])
            path.unlink()
    finally:
        tracemalloc.stop()
    assert ran >= len(MAKERS) * len(MUTATIONS), f"the budget ran out after {ran} cases"


@pytest.mark.timeout(120)
def test_info_on_fuzzed_files_prints_one_line(tmp_path, valid_bytes, capfd, monkeypatch):
    monkeypatch.setenv("ALPHASCOOP_CACHE_DIR", str(tmp_path / "cache"))
    deadline = time.process_time() + BUDGET_S
    ran = 0
    for kind, how, seed in cases(list(MAKERS), CLI_CASES_PER_KIND, SEED + 1):
        if time.process_time() > deadline:
            break
        ran += 1
        path = write_case(valid_bytes[kind], MAKERS[kind][0], how, seed, tmp_path)
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            status = main(["info", str(path)])
        out, err = capfd.readouterr()
        assert not caught, (kind, how, seed, [str(w.message) for w in caught])
        if status == 0:
            assert err == "" and out.startswith(f"file        {path}"), (kind, how, seed)
        else:
            assert status == 1 and out == "", (kind, how, seed, status)
            assert err.startswith("alphascoop: error: ") and err.count("\n") == 1, err
            assert not NOT_PLAIN.search(err), err
    assert ran >= len(MAKERS), f"the budget ran out after {ran} cases"


@pytest.mark.parametrize("ext", sorted({ext for ext, _ in MAKERS.values()}))
@pytest.mark.parametrize("content", ["binary", "latin", "text"])
def test_garbage_of_every_extension_is_named_in_words(tmp_path, ext, content):
    rng = np.random.default_rng(3)
    raw = {"binary": rng.integers(0, 256, 3000, dtype=np.uint8).tobytes(),
           "latin": "\u00c2\u00e9 caf\u00e9 \u00ff\n".encode("latin-1") * 50,
           "text": b"hello world, this is not a point file\n" * 20}[content]
    path = tmp_path / f"garbage{ext}"
    path.write_bytes(raw)
    with pytest.raises(FileFormatError) as info:
        read_points(path)
    assert_plain(str(info.value), path)

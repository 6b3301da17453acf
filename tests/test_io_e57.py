"""E57 scans: every scan with its pose, one chosen scan, spherical coordinates, invalid flags,
intensity and colour. Files are written with pye57 (its writer and libE57Format's nodes);
expected points are computed here with numpy from the written values."""

from __future__ import annotations

import numpy as np
import pye57
import pytest

from core.errors import FileFormatError
from core.io import read_points

RNG = np.random.default_rng(57)


def _rotation(q: np.ndarray) -> np.ndarray:
    """Rotation matrix of a unit quaternion (w, x, y, z)."""
    w, x, y, z = q / np.linalg.norm(q)
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                     [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                     [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])


def _cartesian_scans(path, scans):
    """Write scans given as (xyz, invalid, intensity, rgb, quaternion, translation)."""
    with pye57.E57(str(path), mode="w") as e57:
        for xyz, invalid, intensity, rgb, q, t in scans:
            data = {"cartesianX": xyz[:, 0], "cartesianY": xyz[:, 1], "cartesianZ": xyz[:, 2],
                    "cartesianInvalidState": invalid.astype(np.int8),
                    "intensity": intensity, "colorRed": rgb[:, 0], "colorGreen": rgb[:, 1],
                    "colorBlue": rgb[:, 2]}
            e57.write_scan_raw(data, rotation=q, translation=t)


def _scan(n: int, q, t):
    xyz = RNG.uniform(-5, 5, size=(n, 3)).astype(np.float32).astype(np.float64)
    invalid = np.zeros(n, dtype=np.int8)
    invalid[::4] = 2
    intensity = RNG.uniform(0, 1, n).astype(np.float32).astype(np.float64)
    rgb = RNG.integers(0, 256, size=(n, 3)).astype(np.uint8)
    return xyz, invalid, intensity, rgb, np.asarray(q, dtype=float), np.asarray(t, dtype=float)


@pytest.fixture
def two_scans(tmp_path):
    q = np.array([np.cos(0.3), 0.0, 0.0, np.sin(0.3)])  # 0.6 rad about z
    scans = [_scan(40, [1, 0, 0, 0], [0, 0, 0]), _scan(24, q, [10.0, -2.0, 1.5])]
    _cartesian_scans(tmp_path / "two.e57", scans)
    return tmp_path / "two.e57", scans


def _expected(scan):
    xyz, invalid, intensity, rgb, q, t = scan
    keep = invalid == 0
    return (xyz @ _rotation(q).T + t)[keep], intensity[keep], rgb[keep]


def test_every_scan_with_its_pose(two_scans):
    path, scans = two_scans
    ps = read_points(path)
    expected = [_expected(s) for s in scans]
    np.testing.assert_allclose(ps.points, np.vstack([e[0] for e in expected]), atol=1e-9)
    np.testing.assert_allclose(ps.attributes["intensity"], np.concatenate(
        [e[1] for e in expected]), rtol=1e-6)
    np.testing.assert_array_equal(ps.attributes["colors"], np.vstack([e[2] for e in expected]))
    assert "E57: 2 scan(s), poses applied" in ps.report.notes
    assert ps.report.count_line() == "48 of 64 records read (16 are flagged invalid)"


@pytest.mark.parametrize("index", [0, 1])
def test_one_chosen_scan(two_scans, index):
    path, scans = two_scans
    ps = read_points(path, scan=index)
    np.testing.assert_allclose(ps.points, _expected(scans[index])[0], atol=1e-9)
    assert f"E57: scan {index} of 2" in ps.report.notes


def test_scan_out_of_range_and_scan_on_other_formats(two_scans, tmp_path):
    with pytest.raises(FileFormatError, match=r"no scan 2; the file has scans 0\.\.1"):
        read_points(two_scans[0], scan=2)
    np.save(tmp_path / "p.npy", np.zeros((3, 3)))
    with pytest.raises(FileFormatError, match="E57 files only"):
        read_points(tmp_path / "p.npy", scan=0)


def _spherical(path, rae: np.ndarray, state: np.ndarray, q, t) -> None:
    """One spherical scan through libE57Format's node API (pye57 writes Cartesian only)."""
    from pye57 import libe57

    with pye57.E57(str(path), mode="w") as e57:
        imf = e57.image_file
        scan = libe57.StructureNode(imf)
        scan.set("guid", libe57.StringNode(imf, "{spherical-test}"))
        pose = libe57.StructureNode(imf)
        rot, tr = libe57.StructureNode(imf), libe57.StructureNode(imf)
        for name, value in zip("wxyz", q, strict=True):
            rot.set(name, libe57.FloatNode(imf, float(value)))
        for name, value in zip("xyz", t, strict=True):
            tr.set(name, libe57.FloatNode(imf, float(value)))
        pose.set("rotation", rot)
        pose.set("translation", tr)
        scan.set("pose", pose)
        proto = libe57.StructureNode(imf)
        names = ["sphericalRange", "sphericalAzimuth", "sphericalElevation"]
        for name in names:
            proto.set(name, libe57.FloatNode(imf, 0.0, libe57.E57_DOUBLE, -1e3, 1e3))
        proto.set("sphericalInvalidState", libe57.IntegerNode(imf, 0, 0, 2))
        points = libe57.CompressedVectorNode(imf, proto, libe57.VectorNode(imf, True))
        scan.set("points", points)
        e57.data3d.append(scan)
        columns = [np.ascontiguousarray(rae[:, i]) for i in range(3)] + [state.astype(np.int8)]
        buffers = libe57.VectorSourceDestBuffer()
        for name, column in zip([*names, "sphericalInvalidState"], columns, strict=True):
            buffers.append(libe57.SourceDestBuffer(imf, name, column, len(rae), True, True))
        writer = points.writer(buffers)
        writer.write(len(rae))
        writer.close()


def test_spherical_scan_with_pose_and_invalid_ranges(tmp_path):
    n = 30
    rae = np.column_stack([RNG.uniform(1, 20, n), RNG.uniform(-np.pi, np.pi, n),
                           RNG.uniform(-1.2, 1.2, n)])
    state = np.zeros(n, dtype=np.int8)
    state[[3, 7]] = 1  # range unknown: direction only, no point
    q, t = np.array([0.9, 0.1, -0.2, 0.3]), np.array([100.0, 200.0, 5.0])
    q /= np.linalg.norm(q)
    _spherical(tmp_path / "s.e57", rae, state, q, t)
    r, az, el = rae.T
    local = np.column_stack([r * np.cos(el) * np.cos(az), r * np.cos(el) * np.sin(az),
                             r * np.sin(el)])
    ps = read_points(tmp_path / "s.e57")
    np.testing.assert_allclose(ps.points, (local @ _rotation(q).T + t)[state == 0], atol=1e-9)
    # every record counts as read; those left out are named with their reason
    assert ps.report.n_read == n and ps.report.n_points == n - 2
    assert ps.report.count_line() == "28 of 30 records read (2 have no range (direction only))"
    assert "points      28 of 30 records read (2 have no range" in "\n".join(ps.report.lines())


def test_not_an_e57_file(tmp_path):
    (tmp_path / "x.e57").write_bytes(b"ASTM-E57" + bytes(2000))
    with pytest.raises(FileFormatError, match="not a readable E57 file"):
        read_points(tmp_path / "x.e57")


def test_cli_scan_option(two_scans, tmp_path, monkeypatch, capsys):
    import json

    from app.cli import main

    monkeypatch.setenv("ALPHASCOOP_CACHE_DIR", str(tmp_path / "cache"))
    path, scans = two_scans
    assert main(["info", str(path), "--scan", "1", "--json"]) == 0
    report = json.loads(capsys.readouterr().out)["load"]
    assert report["n_points"] == len(_expected(scans[1])[0])
    assert report["n_read"] == len(scans[1][0])  # the records, invalid ones too
    assert report["skipped"] == [{"count": 6, "reason": "are flagged invalid"}]
    assert main(["info", str(path), "--scan", "x"]) == 2
    assert "expected a whole number from 0" in capsys.readouterr().err

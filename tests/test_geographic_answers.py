"""Geographic answers that looked right and were not: the perimeter of a shape cut at the
antimeridian, a shape around a pole, a stray latitude of 95, and `ele` heights."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from app.cli import main
from core.errors import FileFormatError
from core.io import read_points


@pytest.fixture(autouse=True)
def cache(tmp_path, monkeypatch):
    monkeypatch.setenv("ALPHASCOOP_CACHE_DIR", str(tmp_path / "cache"))


def _csv(path: Path, rows: np.ndarray, header: str = "lon,lat") -> Path:
    path.write_text(header + "\n" + "".join(",".join(repr(float(v)) for v in row) + "\n"
                                            for row in rows))
    return path


def _run(capsys, *argv) -> tuple[int, str, str]:
    code = main([str(a) for a in argv])
    out, err = capsys.readouterr()
    return code, out, err


def _strip(lon0: float) -> np.ndarray:
    """A north-south strip of points 4 degrees wide, 14 degrees long, centred on lon0."""
    rng = np.random.default_rng(7)
    lon = lon0 + rng.uniform(-2.0, 2.0, 600)
    lat = rng.uniform(-24.0, -10.0, 600)
    return np.column_stack([(lon + 180.0) % 360.0 - 180.0, lat])


def test_the_perimeter_across_the_antimeridian_leaves_out_the_cut(tmp_path, capsys):
    """The same strip centred on 180 and on 150: the projection is centred on the data, so
    both give the same shape in metres and must give the same ellipsoidal perimeter; the
    cut along +-180 (two edges of 14 degrees) is no part of it."""
    measured = {}
    for lon0 in (180.0, 150.0):
        path = _csv(tmp_path / f"strip{lon0:.0f}.csv", _strip(lon0))
        code, out, _ = _run(capsys, "info", path, "--json", "--alpha", "60000")
        info = json.loads(out)
        code, out, _ = _run(capsys, "export", path, "--alpha", "60000", "-o",
                            tmp_path / f"strip{lon0:.0f}.geojson")
        assert code == 0
        props = json.loads((tmp_path / f"strip{lon0:.0f}.geojson").read_text()
                           )["features"][0]["properties"]
        measured[lon0] = (info["perimeter_m"], props["perimeter_m"], info["area_m2"])
    across, away = measured[180.0], measured[150.0]
    assert across[0] == pytest.approx(away[0], rel=1e-6)  # info's line
    assert across[1] == pytest.approx(away[1], rel=1e-6)  # the GeoJSON properties
    assert across[2] == pytest.approx(away[2], rel=1e-6)


def test_a_shape_around_a_pole_is_measured_and_refused_in_lonlat(tmp_path, capsys):
    rng = np.random.default_rng(0)
    angle = np.linspace(0.0, 2.0 * np.pi, 500, endpoint=False)
    lat = 89.0 + 0.3 * np.sin(3.0 * angle) + rng.normal(0.0, 0.01, 500)
    path = _csv(tmp_path / "pole.csv", np.column_stack([np.degrees(angle) - 180.0, lat]))
    code, out, err = _run(capsys, "info", path, "--json")
    assert code == 0, err
    info = json.loads(out)
    assert info["area_m2"] == pytest.approx(info["area"], rel=1e-3)
    for ext in (".geojson", ".wkt"):
        code, _, err = _run(capsys, "export", path, "-o", tmp_path / f"pole{ext}")
        assert code == 1 and "goes around a pole" in err and "unexpected" not in err
        assert not (tmp_path / f"pole{ext}").exists()
    code, _, err = _run(capsys, "export", path, "-o", tmp_path / "pole.svg")
    assert code == 0, err


def test_a_latitude_of_95_among_degrees_is_refused_naming_the_row(tmp_path):
    rng = np.random.default_rng(1)
    rows = np.column_stack([2.0 + rng.random(50), 48.0 + rng.random(50)])
    rows[10, 1] = 95.0
    with pytest.raises(FileFormatError, match=r"latitude 95 at row 11 is not in degrees"):
        read_points(_csv(tmp_path / "stray.csv", rows))
    metres = np.column_stack([np.arange(50) * 1e4, np.arange(50) % 7])
    ps = read_points(_csv(tmp_path / "metres.csv", metres))  # mostly out of range: numbers
    assert ps.report.georef is None and np.array_equal(ps.points, metres)


@pytest.mark.parametrize("name", ["ele", "elevation", "height", "alt", "altitude", "z"])
def test_height_names_are_read(tmp_path, name):
    rng = np.random.default_rng(2)
    rows = np.column_stack([2.0 + rng.random(60), 48.0 + rng.random(60), 100 * rng.random(60)])
    path = _csv(tmp_path / "track.csv", rows, f"lon,lat,{name}")
    ps = read_points(path)
    assert ps.report.georef is not None and ps.report.georef.height == "altitude"
    np.testing.assert_array_equal(ps.attributes["altitude"], rows[:, 2])
    ps = read_points(path, columns=f"lon,lat,{name}")
    assert ps.points.shape == (60, 3) and ps.report.georef.height == "z"
    np.testing.assert_array_equal(ps.points[:, 2], rows[:, 2])

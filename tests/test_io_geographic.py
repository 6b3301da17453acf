"""Longitude/latitude columns are built in metres in a local conformal projection, and exports
go back to WGS 84 longitude/latitude; checked against pyproj and shapely directly."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
import shapely
from pyproj import CRS, Geod, Transformer
from scipy.spatial import ConvexHull

from app.cli import main
from core import AlphaComplex
from core.export import write_shape
from core.io import read_points

GEOD = Geod(ellps="WGS84")
WGS84 = CRS.from_epsg(4326)


@pytest.fixture(autouse=True)
def cache(tmp_path, monkeypatch):
    monkeypatch.setenv("ALPHASCOOP_CACHE_DIR", str(tmp_path / "cache"))


def _lonlat(n: int, lon0: float, lat0: float, radius_deg: float, seed: int = 0) -> np.ndarray:
    """(n, 2) random longitude/latitude within radius_deg of (lon0, lat0), lon in [-180, 180)."""
    rng = np.random.default_rng(seed)
    lon = lon0 + rng.uniform(-radius_deg, radius_deg, n)
    lat = np.clip(lat0 + rng.uniform(-radius_deg, radius_deg, n), -89.9, 89.9)
    return np.column_stack([(lon + 180.0) % 360.0 - 180.0, lat])


def _csv(path: Path, lonlat: np.ndarray, header: str = "lon,lat", alt: bool = False) -> Path:
    cols = [lonlat[:, 0], lonlat[:, 1]] if header.startswith("lon") else [lonlat[:, 1],
                                                                            lonlat[:, 0]]
    if alt:
        cols.append(np.linspace(100.0, 200.0, len(lonlat)))
    rows = "".join(",".join(repr(float(v)) for v in row) + "\n" for row in zip(*cols, strict=True))
    path.write_text(header + "\n" + rows)
    return path


def _hull_lonlat(lonlat: np.ndarray, crs: str, segment_m: float | None = None
                 ) -> shapely.Polygon:
    """Convex hull of the points in `crs` (pyproj directly), as a lon/lat polygon (its edges
    split every `segment_m` metres in the projection, if given)."""
    fwd = Transformer.from_crs("EPSG:4326", crs, always_xy=True)
    inv = Transformer.from_crs(crs, "EPSG:4326", always_xy=True)
    xy = np.column_stack(fwd.transform(lonlat[:, 0], lonlat[:, 1]))
    hull = shapely.Polygon(xy[ConvexHull(xy).vertices])
    ring = shapely.get_coordinates(hull if segment_m is None
                                   else shapely.segmentize(hull, segment_m))
    return shapely.Polygon(np.column_stack(inv.transform(ring[:, 0], ring[:, 1])))


def test_lonlat_columns_become_utm_metres(tmp_path):
    lonlat = _lonlat(300, 12.5, 41.9, 0.3)  # around Rome: UTM zone 33N
    ps = read_points(_csv(tmp_path / "rome.csv", lonlat))
    georef = ps.report.georef
    assert georef is not None and georef.crs == "EPSG:32633" and "UTM zone 33N" in georef.name
    want = np.column_stack(Transformer.from_crs("EPSG:4326", "EPSG:32633", always_xy=True)
                           .transform(lonlat[:, 0], lonlat[:, 1]))
    np.testing.assert_allclose(ps.points, want, rtol=0, atol=1e-6)
    assert any(line.startswith("projection  UTM zone 33N") for line in ps.report.lines())
    assert ps.report.to_dict()["georef"]["crs"] == "EPSG:32633"
    assert 0.9996 <= georef.scale[0] <= georef.scale[1] < 1.001  # UTM: k0 = 0.9996


def test_latitude_first_and_altitude(tmp_path):
    lonlat = _lonlat(100, -70.6, -33.4, 0.2)  # Santiago: UTM zone 19S
    path = _csv(tmp_path / "scl.csv", lonlat, header="latitude,longitude,altitude", alt=True)
    flat = read_points(path)
    assert flat.points.shape == (100, 2) and flat.report.georef.crs == "EPSG:32719"
    np.testing.assert_allclose(flat.attributes["altitude"], np.linspace(100, 200, 100))
    solid = read_points(path, columns="longitude,latitude,altitude")
    assert solid.points.shape == (100, 3) and solid.report.georef.height == "z"
    np.testing.assert_allclose(solid.points[:, :2], flat.points)
    np.testing.assert_allclose(solid.points[:, 2], np.linspace(100, 200, 100))


def test_geojson_goes_back_to_lonlat_rfc7946(tmp_path):
    lonlat = _lonlat(400, 12.5, 41.9, 0.3)
    ps = read_points(_csv(tmp_path / "rome.csv", lonlat))
    ac = AlphaComplex.from_points(ps.points)
    report = write_shape(ac, 1e9, tmp_path / "hull.geojson", georef=ps.report.georef)
    doc = json.loads(Path(report.path).read_text())
    geom = shapely.geometry.shape(doc["features"][0]["geometry"])
    hull = _hull_lonlat(lonlat, "EPSG:32633")
    # the same vertices as pyproj's own projection, hull and inverse (lon/lat to 1e-9 degrees)
    got = {tuple(np.round(c, 9)) for c in shapely.get_coordinates(geom)}
    assert got == {tuple(np.round(c, 9)) for c in shapely.get_coordinates(hull)}
    assert all(p.exterior.is_ccw for p in geom.geoms)  # RFC 7946 section 3.1.6
    assert shapely.covers(geom.buffer(1e-9), shapely.points(lonlat)).all()
    props = doc["features"][0]["properties"]
    area, perimeter = GEOD.geometry_area_perimeter(hull)
    assert props["area_m2"] == pytest.approx(abs(area), rel=1e-9)
    assert props["perimeter_m"] == pytest.approx(perimeter, rel=1e-9)
    # the planar area is the ellipsoid's times the squared scale factor of the projection
    low, high = ps.report.georef.scale
    assert low**2 * (1 - 1e-5) <= props["area"] / abs(area) <= high**2 * (1 + 1e-5)
    assert props["georef"]["crs"] == "EPSG:32633" and props["units"] == "m"
    assert "m²" in report.line() and "WGS 84" in report.line()


def test_wkt_and_csv_name_the_crs(tmp_path):
    lonlat = _lonlat(200, 2.35, 48.85, 0.2)
    ps = read_points(_csv(tmp_path / "paris.csv", lonlat))
    ac = AlphaComplex.from_points(ps.points)
    alpha = float(ac.optimal_alpha())
    wkt = write_shape(ac, alpha, tmp_path / "p.wkt", georef=ps.report.georef)
    csv = write_shape(ac, alpha, tmp_path / "q.csv", georef=ps.report.georef)
    assert csv.crs_file == str(tmp_path / "q.prj")
    assert wkt.crs_file == str(tmp_path / "p.prj") and "CRS in" in wkt.line()
    assert CRS.from_wkt((tmp_path / "p.prj").read_text()).equals(WGS84, ignore_axis_order=True)
    assert CRS.from_wkt((tmp_path / "q.prj").read_text()).equals(WGS84, ignore_axis_order=True)
    geom = shapely.from_wkt((tmp_path / "p.wkt").read_text())
    assert abs(GEOD.geometry_area_perimeter(geom)[0]) == pytest.approx(
        wkt.metadata["area_m2"], rel=1e-9)
    rows = (tmp_path / "q.csv").read_text().splitlines()
    assert rows[0] == "polygon,ring,role,vertex,lon,lat"
    lon, lat = (float(v) for v in rows[1].split(",")[-2:])
    assert 2.0 < lon < 2.7 and 48.5 < lat < 49.2


def test_antimeridian_is_centred_and_cut(tmp_path):
    lonlat = _lonlat(300, 180.0, -17.0, 1.5)  # Fiji, across +-180
    ps = read_points(_csv(tmp_path / "fiji.csv", lonlat))
    georef = ps.report.georef
    assert np.ptp(ps.points[:, 0]) < 400_000  # one piece in metres, not two 40,000 km apart
    ac = AlphaComplex.from_points(ps.points)
    report = write_shape(ac, 1e9, tmp_path / "fiji.geojson", georef=georef)
    geom = shapely.geometry.shape(json.loads(Path(report.path).read_text())
                                  ["features"][0]["geometry"])
    lo, _, hi, _ = geom.bounds
    assert -180.0 <= lo and hi <= 180.0 and len(geom.geoms) == 2  # cut in two at +-180
    # edges are straight in the projection; the export follows them within a 1 km step
    hull = _hull_lonlat(lonlat, georef.crs, segment_m=1000.0)
    assert abs(GEOD.geometry_area_perimeter(geom)[0]) == pytest.approx(
        abs(GEOD.geometry_area_perimeter(hull)[0]), rel=1e-7)


@pytest.mark.parametrize("lat0", [88.0, -88.0])
def test_poles_get_a_transverse_mercator(tmp_path, lat0):
    lonlat = _lonlat(300, 0.0, lat0, 2.0)
    lonlat[:, 0] = np.random.default_rng(1).uniform(-180, 180, len(lonlat))  # all around
    ps = read_points(_csv(tmp_path / "pole.csv", lonlat))
    georef = ps.report.georef
    assert "transverse Mercator" in georef.name and georef.scale[1] < 1.01
    back = georef.to_lonlat(ps.points)
    np.testing.assert_allclose(back[:, 1], lonlat[:, 1], atol=1e-9)
    np.testing.assert_allclose((back[:, 0] - lonlat[:, 0] + 180) % 360 - 180, 0, atol=1e-7)


def test_not_degrees_or_whole_globe_are_read_as_numbers_with_a_note(tmp_path):
    metres = _csv(tmp_path / "m.csv", np.column_stack([np.arange(50) * 1e4, np.arange(50) % 7]))
    ps = read_points(metres)
    assert ps.report.georef is None and any("not in degrees" in n for n in ps.report.notes)
    globe = np.column_stack([np.linspace(-179, 179, 60), np.tile([-60.0, 0.0, 60.0], 20)])
    ps = read_points(_csv(tmp_path / "g.csv", globe))
    assert ps.report.georef is None and any("no local projection" in n for n in ps.report.notes)
    assert np.array_equal(ps.points, globe)


def test_columns_by_index_stay_degrees(tmp_path):
    lonlat = _lonlat(50, 12.5, 41.9, 0.3)
    ps = read_points(_csv(tmp_path / "rome.csv", lonlat), columns="0,1")
    assert ps.report.georef is None and np.array_equal(ps.points, lonlat)


def test_cli_reports_projection_and_metres(tmp_path, capsys):
    path = _csv(tmp_path / "rome.csv", _lonlat(300, 12.5, 41.9, 0.3))
    assert main(["info", str(path)]) == 0
    out = capsys.readouterr().out
    assert "projection  UTM zone 33N (EPSG:32633), metres" in out and "area (m²)" in out
    assert main(["export", str(path), "-o", str(tmp_path / "r.geojson"), "--sidecar"]) == 0
    out = capsys.readouterr().out
    assert "m²" in out and "perimeter" in out
    meta = json.loads((tmp_path / "r.geojson.json").read_text())
    assert meta["georef"]["crs"] == "EPSG:32633" and meta["area_m2"] > 0

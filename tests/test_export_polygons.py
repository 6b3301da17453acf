"""2D exports: polygons with holes whose area equals the complex's area, in every format."""

from __future__ import annotations

import json
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st
from reference import data_dir, needs_data

from core import AlphaComplex
from core.errors import FileFormatError
from core.export import write_shape
from core.export.polygons import shape_polygons

DATA = data_dir()


@pytest.fixture(scope="module")
def annulus() -> AlphaComplex:
    """Complex of 500 random points in an annulus (a hole) plus a separate island cluster."""
    rng = np.random.default_rng(5)
    r = np.sqrt(rng.uniform(0.5**2, 1.0, 450))
    t = rng.uniform(0, 2 * np.pi, 450)
    ring = np.column_stack([r * np.cos(t), r * np.sin(t)])
    island = rng.uniform(-0.1, 0.1, (50, 2))  # inside the hole
    return AlphaComplex.from_points(np.vstack([ring, island]))


def test_polygons_have_holes_and_area(annulus):
    shape = annulus.shape(0.12)
    geom = shape_polygons(annulus, shape)
    assert geom.is_valid
    assert geom.area == pytest.approx(shape.measure, rel=1e-9)
    assert any(len(p.interiors) for p in geom.geoms)  # the annulus keeps its hole
    assert len(geom.geoms) >= 2  # the island is a polygon of its own


def test_geojson_round_trip(tmp_path, annulus):
    write_shape(annulus, 0.12, tmp_path / "s.geojson", source="pts.csv")
    doc = json.loads((tmp_path / "s.geojson").read_text())
    feature = doc["features"][0]
    geom = shapely.geometry.shape(feature["geometry"])
    assert geom.area == pytest.approx(annulus.shape(0.12).measure, rel=1e-9)
    assert feature["properties"]["alpha"] == 0.12
    assert feature["properties"]["source"] == "pts.csv"


def test_wkt_round_trip(tmp_path, annulus):
    write_shape(annulus, 0.12, tmp_path / "s.wkt")
    geom = shapely.from_wkt((tmp_path / "s.wkt").read_text())
    assert geom.area == pytest.approx(annulus.shape(0.12).measure, rel=1e-9)


def test_rings_csv_round_trip(tmp_path, annulus):
    write_shape(annulus, 0.12, tmp_path / "s.csv")
    table = np.genfromtxt(tmp_path / "s.csv", delimiter=",", names=True, dtype=None,
                          encoding="utf-8")
    area = 0.0
    for key in {(int(p), int(r)) for p, r in zip(table["polygon"], table["ring"], strict=True)}:
        sel = (table["polygon"] == key[0]) & (table["ring"] == key[1])
        ring = shapely.LinearRing(np.column_stack([table["x"][sel], table["y"][sel]]))
        sign = 1 if key[1] == 0 else -1
        area += sign * shapely.Polygon(ring).area
    assert area == pytest.approx(annulus.shape(0.12).measure, rel=1e-9)


def test_rings_csv_rows_are_the_polygon_rings(tmp_path, annulus):
    write_shape(annulus, 0.12, tmp_path / "s.csv")
    lines = (tmp_path / "s.csv").read_text().splitlines()
    assert lines[0] == "polygon,ring,role,vertex,x,y"
    want = [f"{p},{r},{'shell' if r == 0 else 'hole'},{i},{x!r},{y!r}"
            for p, poly in enumerate(shape_polygons(annulus, annulus.shape(0.12)).geoms)
            for r, ring in enumerate([poly.exterior, *poly.interiors])
            for i, (x, y) in enumerate(ring.coords)]
    assert lines[1:] == want
    assert any(",hole," in line for line in want)


def test_singular_edges_exported_as_lines(tmp_path, annulus):
    far = np.array([[3.0, 3.0], [3.1, 3.0], [3.2, 3.01], [-3.0, 2.0], [-3.0, 2.2]])
    ac = AlphaComplex.from_points(np.vstack([annulus.points, far]))
    shape = ac.shape(0.12)
    edges = np.asarray(shape.singular(1))
    assert len(edges) >= 3
    write_shape(ac, 0.12, tmp_path / "s.geojson")
    features = json.loads((tmp_path / "s.geojson").read_text())["features"]
    lines = shapely.geometry.shape(features[1]["geometry"])
    assert features[1]["properties"]["role"] == "singular_edges"
    got = {tuple(map(tuple, line.coords)) for line in lines.geoms}
    assert got == {tuple(map(tuple, ac.points[e])) for e in edges}
    write_shape(ac, 0.12, tmp_path / "s.svg")
    svg = ET.parse(tmp_path / "s.svg").getroot().findall("{http://www.w3.org/2000/svg}path")
    assert sum(p.get("fill") == "none" for p in svg) == len(edges)


def test_svg_is_xml_with_one_path_per_polygon(tmp_path, annulus):
    write_shape(annulus, 0.12, tmp_path / "s.svg")
    root = ET.parse(tmp_path / "s.svg").getroot()
    paths = root.findall("{http://www.w3.org/2000/svg}path")
    assert len(paths) >= len(shape_polygons(annulus, annulus.shape(0.12)).geoms)
    assert root.get("viewBox")


def test_polygon_formats_refuse_3d(tmp_path):
    ac = AlphaComplex.from_points(np.random.default_rng(0).normal(size=(40, 3)))
    with pytest.raises(FileFormatError, match="2D"):
        write_shape(ac, 1.0, tmp_path / "s.geojson")
    assert not (tmp_path / "s.geojson").exists()


def test_planar_3d_input_exports_polygons(tmp_path):
    rng = np.random.default_rng(2)
    xy = rng.uniform(size=(200, 2))
    pts = np.column_stack([xy, 0.5 * xy[:, 0] + 0.25 * xy[:, 1]])  # a tilted plane
    ac = AlphaComplex.from_points(pts)
    assert ac.dim == 2
    write_shape(ac, 0.1, tmp_path / "s.wkt")
    geom = shapely.from_wkt((tmp_path / "s.wkt").read_text())
    assert geom.area == pytest.approx(ac.shape(0.1).measure, rel=1e-9)
    write_shape(ac, 0.1, tmp_path / "s.geojson")
    props = json.loads((tmp_path / "s.geojson").read_text())["features"][0]["properties"]
    origin, axes = np.array(props["plane_origin"]), np.array(props["plane_axes"])
    corner = np.asarray(geom.geoms[0].exterior.coords)[0]
    lifted = origin + corner @ axes  # back on the tilted plane z = x/2 + y/4
    assert lifted[2] == pytest.approx(0.5 * lifted[0] + 0.25 * lifted[1])


@settings(max_examples=25, deadline=None)
@given(st.integers(0, 10_000), st.floats(0.02, 0.4))
def test_polygon_area_equals_measure(seed, alpha):
    rng = np.random.default_rng(seed)
    pts = np.round(rng.uniform(size=(80, 2)), 1 + seed % 3)  # coarse lattices touch a lot
    pts = np.unique(pts, axis=0)
    if len(pts) < 4:
        return
    ac = AlphaComplex.from_points(pts)
    shape = ac.shape(alpha)
    geom = shape_polygons(ac, shape)
    assert geom.is_valid
    assert geom.area == pytest.approx(shape.measure, rel=1e-9, abs=1e-12)


@needs_data
def test_airports_geojson(tmp_path):
    from core.io import read_points

    ac = AlphaComplex.from_points(read_points(DATA / "us_airports.csv").points)  # metres
    report = write_shape(ac, 150_000.0, tmp_path / "airports.geojson")  # no georef: metres
    geom = shapely.geometry.shape(json.loads(Path(report.path).read_text())
                                  ["features"][0]["geometry"])
    measure = ac.shape(150_000.0).measure
    assert geom.is_valid and measure > 0 and geom.area == pytest.approx(measure, rel=1e-9)

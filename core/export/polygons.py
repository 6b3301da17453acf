"""2D shapes as polygons with holes (shapely): GeoJSON, WKT, SVG and CSV of rings."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import shapely

from core.export.csvrows import format_rows, write_rows
from core.export.geographic import rfc7946, to_lonlat
from core.export.metadata import sidecar_text
from core.export.rings import ring_order, successors
from core.geometry.georef import Georef, geodesic_area_perimeter, geodesic_length


def boundary_rings(points: np.ndarray, edges: np.ndarray) -> list[np.ndarray]:
    """Closed rings ((k, 2) float64, first point repeated last) of oriented boundary edges."""
    if len(edges) == 0:
        return []
    order, offsets = ring_order(successors(points, edges))
    tails = points[edges[order, 0]]
    return [np.vstack([r, r[:1]]) for r in np.split(tails, offsets[1:])]


def signed_area(ring: np.ndarray) -> float:
    """Shoelace area of a closed (k, 2) ring: positive when counter-clockwise."""
    x, y = ring[:, 0], ring[:, 1]
    return 0.5 * float(np.dot(x[:-1], y[1:]) - np.dot(x[1:], y[:-1]))


def shape_polygons(ac, shape) -> shapely.MultiPolygon:
    """The regularized 2D shape as a valid MultiPolygon (holes inside their shells)."""
    rings = boundary_rings(np.asarray(ac.points), np.asarray(shape.regular_facets))
    areas = np.array([signed_area(r) for r in rings])
    shells = [shapely.Polygon(r) for r, a in zip(rings, areas, strict=True) if a > 0]
    holes = [r for r, a in zip(rings, areas, strict=True) if a < 0]
    owner = _hole_owners(shells, [shapely.Polygon(h) for h in holes])
    polys = [shapely.Polygon(s.exterior, [h for h, o in zip(holes, owner, strict=True) if o == i])
             for i, s in enumerate(shells)]
    geom = shapely.MultiPolygon(polys)
    if not geom.is_valid:
        geom = shapely.make_valid(geom)
        parts = [g for g in getattr(geom, "geoms", [geom]) if g.geom_type.endswith("Polygon")]
        geom = shapely.MultiPolygon([p for g in parts for p in getattr(g, "geoms", [g])])
    return geom


def _hole_owners(shells: list, holes: list) -> np.ndarray:
    """(h,) index of the smallest shell covering each hole (-1 if none)."""
    owner = np.full(len(holes), -1, dtype=np.int64)
    if not holes or not shells:
        return owner
    tree = shapely.STRtree(shells)
    hole_idx, shell_idx = tree.query(holes, predicate="covered_by")
    area = shapely.area(np.asarray(shells, dtype=object))[shell_idx]
    order = np.lexsort((area, hole_idx))
    first = np.concatenate([[True], hole_idx[order][1:] != hole_idx[order][:-1]])
    owner[hole_idx[order][first]] = shell_idx[order][first]
    return owner


def singular_lines(ac, shape) -> shapely.MultiLineString:
    """SINGULAR edges (dangling, in no triangle) as line segments."""
    edges = np.asarray(shape.singular(1), dtype=np.int64).reshape(-1, 2)
    if len(edges) == 0:
        return shapely.MultiLineString()
    return shapely.multilinestrings(shapely.linestrings(np.asarray(ac.points)[edges]))


def _user_coordinates(ac, geometry, georef):
    """`geometry` as the user gave the points: longitude/latitude for geographic input."""
    return geometry if georef is None else to_lonlat(ac, georef, geometry)


def write_geojson(path: Path, ac, shape, meta: dict, georef=None) -> None:
    """FeatureCollection: the polygons (properties = metadata) and any singular edges.

    Geographic input (`georef`, a core.geometry.georef.Georef) is written in WGS 84
    longitude/latitude as RFC 7946 requires: shells counter-clockwise, cut at the antimeridian.
    """
    polygons = rfc7946(_user_coordinates(ac, shape_polygons(ac, shape), georef))
    features = [{"type": "Feature", "properties": {"role": "shape", **meta},
                 "geometry": json.loads(shapely.to_geojson(polygons))}]
    lines = _user_coordinates(ac, singular_lines(ac, shape), georef)
    if not lines.is_empty:
        features.append({"type": "Feature", "properties": {"role": "singular_edges"},
                         "geometry": json.loads(shapely.to_geojson(lines))})
    path.write_text(sidecar_text({"type": "FeatureCollection", "features": features}))


def write_wkt(path: Path, ac, shape, meta: dict, georef=None) -> None:
    """Well-known text of the MultiPolygon, at full precision (longitude/latitude when
    `georef` is given; write_shape names the CRS in a .prj file beside it)."""
    geom = _user_coordinates(ac, shape_polygons(ac, shape), georef)
    path.write_text(shapely.to_wkt(geom, rounding_precision=-1) + "\n")


def write_rings_csv(path: Path, ac, shape, meta: dict, georef=None) -> None:
    """One row per ring vertex: polygon, ring (0 = shell), role, vertex, x, y (lon, lat for
    geographic input)."""
    geom = _user_coordinates(ac, shape_polygons(ac, shape), georef)
    polygons = shapely.get_parts(geom)
    rings, polygon = shapely.get_rings(polygons, return_index=True)  # shell first, then holes
    coords, ring = shapely.get_coordinates(rings, return_index=True)
    ring_no = np.arange(len(rings)) - np.searchsorted(polygon, polygon)
    vertex = np.arange(len(coords)) - np.searchsorted(ring, ring)
    role = np.where(ring_no[ring] == 0, "shell", "hole")
    with open(path, "w", encoding="utf-8", newline="\n") as fh:
        fh.write("polygon,ring,role,vertex,x,y\n" if georef is None
                 else "polygon,ring,role,vertex,lon,lat\n")
        write_rows(fh, "%d,%d,%s,%d,%r,%r\n",
                   [polygon[ring], ring_no[ring], role, vertex, coords[:, 0], coords[:, 1]])


def write_svg(path: Path, ac, shape, meta: dict, georef=None) -> None:
    """An SVG figure: filled polygons (even-odd holes), singular edges as thin lines; always
    in the complex's coordinates (metres in the projection for geographic input)."""
    geom = shape_polygons(ac, shape)
    lo, hi = np.min(ac.points, axis=0), np.max(ac.points, axis=0)
    size = float(np.max(hi - lo)) or 1.0
    pad, width = 0.02 * size, 0.002 * size

    def pts(coords) -> str:
        xy = np.asarray(coords, dtype=np.float64).reshape(-1, 2)
        return format_rows("%r,%r ", [xy[:, 0], -xy[:, 1]]).rstrip()

    paths = [" ".join(f"M {pts(r.coords)} Z" for r in [p.exterior, *p.interiors])
             for p in geom.geoms]
    lines = [f"M {pts(line.coords)}" for line in singular_lines(ac, shape).geoms]
    box = (lo[0] - pad, -hi[1] - pad, hi[0] - lo[0] + 2 * pad, hi[1] - lo[1] + 2 * pad)
    view = " ".join(repr(float(v)) for v in box)
    title = f"alpha shape, alpha={float(shape.alpha):.6g}, area={meta.get('area', 0.0):.6g}"
    body = "".join(f'<path d="{d}" fill="#4c8bd6" fill-rule="evenodd" stroke="#1d3f73" '
                   f'stroke-width="{width!r}"/>' for d in paths)
    body += "".join(f'<path d="{d}" fill="none" stroke="#d1495b" stroke-width="{width!r}"/>'
                    for d in lines)
    path.write_text(f'<svg xmlns="http://www.w3.org/2000/svg" viewBox="{view}">'
                    f"<title>{title}</title>{body}</svg>\n")


POLYGON_WRITERS = {".geojson": write_geojson, ".json": write_geojson, ".wkt": write_wkt,
                   ".svg": write_svg, ".csv": write_rings_csv}


def geographic_metadata(ac, shape, georef: Georef) -> dict:
    """Metadata of a geographic export: the projection (lengths in metres), and for 2D shapes
    the area, perimeter and dangling-edge length measured on the WGS 84 ellipsoid."""
    meta: dict = {"units": "m", "georef": georef.to_dict()}
    if ac.dim == 2:  # measured uncut: edges along +-180 of a cut shape are not its own
        polygons = to_lonlat(ac, georef, shape_polygons(ac, shape), cut=False)
        area, perimeter = (0.0, 0.0) if polygons.is_empty else geodesic_area_perimeter(polygons)
        lines = to_lonlat(ac, georef, singular_lines(ac, shape), cut=False)
        meta["area_m2"] = area
        meta["perimeter_m"] = perimeter
        meta["singular_length_m"] = 0.0 if lines.is_empty else geodesic_length(lines)
    return meta

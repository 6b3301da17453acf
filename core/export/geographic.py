"""2D shapes of geographic input, back in WGS 84 longitude/latitude, measured on the ellipsoid.

GeoJSON (RFC 7946) wants longitude/latitude with counter-clockwise shells, and geometries that
cross the antimeridian cut in two; WKT and CSV get the same coordinates with the CRS named in a
`.prj` file beside them (the GIS convention: OGC WKT of EPSG:4326).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import shapely

from core.errors import InputError
from core.geometry.georef import WGS84, WGS84_NAME, Georef
from core.storage.atomic import atomic_write_text

WORLD = shapely.box(-180.0, -90.0, 180.0, 90.0)
CUT_SEGMENT_M = 1000.0  # edges crossing the antimeridian are split this finely before the cut


def to_lonlat(ac, georef: Georef, geometry, *, cut: bool = True):
    """`geometry` (complex coordinates, metres) in longitude/latitude degrees, cut at +-180.

    A geometry that crosses the antimeridian is densified in metres first, so the cut (a
    straight line in degrees) follows its edges to within centimetres. `cut=False`: the
    longitudes unwrapped around the data's centre (may pass +-180), not cut: for measuring
    on the ellipsoid, where the cut's edges along +-180 are no part of the shape. An
    InputError when the cut cannot be made (a shape around a pole has no polygon in
    longitude/latitude).
    """
    def transform(xy: np.ndarray) -> np.ndarray:
        if ac.dim < ac.ambient_dim:  # planar 3D input: back to the input's x, y first
            xy = np.asarray(ac.to_ambient(xy))[:, :2]
        return georef.to_lonlat(xy)

    lonlat = shapely.transform(geometry, transform)
    if not cut or lonlat.is_empty or WORLD.covers(shapely.envelope(lonlat)):
        return lonlat
    dense = shapely.segmentize(geometry, CUT_SEGMENT_M)
    try:
        return cut_antimeridian(shapely.transform(dense, transform))
    except shapely.errors.GEOSException:
        raise InputError("the shape goes around a pole, so it has no polygon in longitude/"
                         "latitude (GeoJSON, WKT, CSV of rings); export it as .svg (metres in "
                         f"the projection, {georef.name}) or as a mesh") from None


def cut_antimeridian(geometry):
    """Split a geometry whose longitudes pass +-180 into parts within [-180, 180]."""
    if geometry.is_empty:
        return geometry
    lo, _, hi, _ = geometry.bounds
    if lo >= -180.0 and hi <= 180.0:
        return geometry
    parts = [shapely.affinity.translate(shapely.intersection(
        geometry, shapely.affinity.translate(WORLD, xoff=shift)), xoff=-shift)
        for shift in (-360.0, 0.0, 360.0)]
    parts = [p for p in parts if not p.is_empty]
    flat = [g for p in parts for g in shapely.get_parts(p)]
    if geometry.geom_type.endswith("Polygon"):
        return shapely.MultiPolygon([g for g in flat if g.geom_type == "Polygon"])
    return shapely.MultiLineString([g for g in flat if g.geom_type == "LineString"])


def rfc7946(geometry):
    """Counter-clockwise shells and clockwise holes, as RFC 7946 section 3.1.6 asks."""
    return shapely.orient_polygons(geometry, exterior_cw=False)


def write_prj(path: Path) -> Path:
    """The `.prj` file naming the CRS (WGS 84 longitude/latitude) beside `path`."""
    from pyproj import CRS  # imported when asked: pyproj is slow to import

    prj = path.with_suffix(".prj")
    atomic_write_text(prj, CRS.from_user_input(WGS84).to_wkt("WKT1_ESRI") + "\n")
    return prj


__all__ = ["WGS84_NAME", "cut_antimeridian", "rfc7946", "to_lonlat",
           "write_prj"]

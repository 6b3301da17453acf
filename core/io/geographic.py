"""Longitude/latitude columns become metres in a local conformal projection chosen for the data.

UTM (the zone of the data's centre) when every point lies within its zone and UTM's
latitudes; else a transverse Mercator centred on the data (near a pole or across several
zones); else, for data spread over a continent, an oblique stereographic centred on the data.
The centre is the mean of the points as unit vectors, so data across the antimeridian or
around a pole is centred where it is, not at longitude 0.
"""

from __future__ import annotations

import numpy as np

from core.errors import FileFormatError
from core.geometry.georef import Georef

LON_NAMES = ("lon", "lng", "long", "longitude")
LAT_NAMES = ("lat", "latitude")
UTM_SLACK_DEG = 1.0  # points this far past their UTM zone's edges still use the zone
UTM_LATITUDES = (-80.0, 84.0)
TMERC_MAX_DEG = 30.0  # farthest angular distance from a transverse Mercator's central line
ROUND_TRIP_DEG = 1e-7  # projected points must invert to within this (about 1 cm)
SCALE_SAMPLE = 10_000  # points whose scale factor is measured for the report
STEREO_MAX_DEG = 150.0  # farthest from the centre a stereographic is used for (scale 15)


def geographic_axes(names: list[str]) -> tuple[int, int] | None:
    """(longitude index, latitude index) within `names` when both are geographic, else None."""
    lon = [i for i, n in enumerate(names[:2]) if n in LON_NAMES]
    lat = [i for i, n in enumerate(names[:2]) if n in LAT_NAMES]
    return (lon[0], lat[0]) if lon and lat else None


def degrees_problem(lon: np.ndarray, lat: np.ndarray) -> str | None:
    """Why these values are not longitude/latitude degrees, or None if they can be."""
    with np.errstate(invalid="ignore"):
        bad_lon, bad_lat = np.abs(lon) > 360.0, np.abs(lat) > 90.0
    for name, bad, values in (("longitude", bad_lon, lon), ("latitude", bad_lat, lat)):
        if bad.any():
            row = int(np.flatnonzero(bad)[0])
            return f"{name} {values[row]:.6g} at row {row + 1} is not in degrees"
    return None


def refuse_stray_rows(lonlat: np.ndarray, source: str) -> None:
    """FileFormatError when most rows are longitude/latitude degrees but some are not (a
    latitude of 95 among degrees is a wrong row, not a file of plain numbers): the first
    such row is named. Files whose rows are mostly out of range are left to be read as
    plain numbers (columns named lon/lat that hold metres)."""
    with np.errstate(invalid="ignore"):
        bad = (np.abs(lonlat[:, 0]) > 360.0) | (np.abs(lonlat[:, 1]) > 90.0)
    n_bad = int(bad.sum())
    if n_bad == 0 or 2 * n_bad >= len(bad):
        return
    problem = degrees_problem(lonlat[:, 0], lonlat[:, 1])
    more = f" (and {n_bad - 1:,} more row(s))" if n_bad > 1 else ""
    raise FileFormatError(f"{source}: {problem}{more}, while {len(bad) - n_bad:,} rows are: "
                          "fix or remove that row, or pick the columns by index (--columns "
                          "0,1) to read them as plain numbers")


def _unit_vectors(lon: np.ndarray, lat: np.ndarray) -> np.ndarray:
    """(n, 3) points on the unit sphere."""
    lo, la = np.radians(lon), np.radians(lat)
    return np.column_stack([np.cos(la) * np.cos(lo), np.cos(la) * np.sin(lo), np.sin(la)])


def _centre(lon: np.ndarray, lat: np.ndarray) -> tuple[float, float, float]:
    """(lon, lat) of the data's centre and the largest angular distance (deg) from it."""
    vec = _unit_vectors(lon, lat)
    mean = vec.mean(axis=0)
    norm = float(np.linalg.norm(mean))
    if norm < 1e-9:
        return 0.0, 0.0, 180.0
    c = mean / norm
    spread = float(np.degrees(np.arccos(np.clip(vec @ c, -1.0, 1.0))).max())
    return float(np.degrees(np.arctan2(c[1], c[0]))), float(np.degrees(np.arcsin(c[2]))), spread


def _wrap(delta: np.ndarray) -> np.ndarray:
    """Longitude differences in [-180, 180)."""
    return (delta + 180.0) % 360.0 - 180.0


def _utm(lon: np.ndarray, lat: np.ndarray, lon0: float, lat0: float) -> tuple[str, str] | None:
    """('EPSG:326zz', name) when every point fits the UTM zone of the centre, else None."""
    zone = int((lon0 + 180.0) // 6.0) % 60 + 1
    meridian = zone * 6.0 - 183.0
    fits_lon = np.abs(_wrap(lon - meridian)).max() <= 3.0 + UTM_SLACK_DEG
    fits_lat = UTM_LATITUDES[0] <= lat.min() and lat.max() <= UTM_LATITUDES[1]
    if not (fits_lon and fits_lat):
        return None
    north = lat0 >= 0.0
    code = (32600 if north else 32700) + zone
    return f"EPSG:{code}", f"UTM zone {zone}{'N' if north else 'S'} (EPSG:{code})"


def _where(lon0: float, lat0: float) -> str:
    """'38.12N 95.27W'."""
    return (f"{abs(lat0):.4g}{'N' if lat0 >= 0 else 'S'} "
            f"{abs(lon0):.4g}{'E' if lon0 >= 0 else 'W'}")


def _from_central_line(lon: np.ndarray, lat: np.ndarray, lon0: float) -> float:
    """Largest angular distance (deg, spherical) of the points from the great circle of the
    meridian lon0 (which goes on over the poles as the meridian lon0 + 180)."""
    s = np.cos(np.radians(lat)) * np.sin(np.radians(_wrap(lon - lon0)))
    return float(np.degrees(np.arcsin(np.clip(np.abs(s), 0.0, 1.0))).max())


def choose_projection(lon: np.ndarray, lat: np.ndarray) -> tuple[str, str, float] | str:
    """(crs, name, centre longitude) of a local conformal projection for finite lon/lat, or
    why none fits."""
    ok = np.isfinite(lon) & np.isfinite(lat)
    lon, lat = lon[ok], lat[ok]
    if len(lon) == 0:
        return "no finite longitude/latitude"
    lon0, lat0, spread = _centre(lon, lat)
    utm = _utm(lon, lat, lon0, lat0)
    if utm is not None:
        return (*utm, lon0)
    where = _where(lon0, lat0)
    params = f"+lat_0={lat0!r} +lon_0={lon0!r} +k=1 +x_0=0 +y_0=0 +ellps=WGS84 +units=m +no_defs"
    if _from_central_line(lon, lat, lon0) <= TMERC_MAX_DEG:
        return f"+proj=tmerc {params} +type=crs", f"transverse Mercator centred on {where}", lon0
    if spread <= STEREO_MAX_DEG:
        return (f"+proj=stere {params} +type=crs", f"oblique stereographic centred on {where}",
                lon0)
    return (f"the points spread {spread:.0f} degrees from their centre ({where}): no local "
            "projection keeps their shapes; pick planar columns by index with --columns")


def localize(lonlat: np.ndarray, columns: tuple[str, ...], height: str | None
             ) -> tuple[np.ndarray, Georef] | str:
    """(n, 2) metres and the Georef for (n, 2) longitude/latitude, or why they cannot be."""
    problem = degrees_problem(lonlat[:, 0], lonlat[:, 1])
    if problem is not None:
        return problem
    chosen = choose_projection(lonlat[:, 0], lonlat[:, 1])
    if isinstance(chosen, str):
        return chosen
    georef = Georef(crs=chosen[0], name=chosen[1], columns=columns, height=height,
                    scale=_scale_range(chosen[0], lonlat), centre_lon=chosen[2])
    xy = georef.to_metres(lonlat)
    back = georef.to_lonlat(xy)
    with np.errstate(invalid="ignore"):
        off = np.abs(_wrap(back[:, 0] - lonlat[:, 0])) + np.abs(back[:, 1] - lonlat[:, 1])
    if np.nanmax(off, initial=0.0) > ROUND_TRIP_DEG:
        return f"{georef.name} does not map these points back to themselves"
    return xy, georef


def _scale_range(crs: str, lonlat: np.ndarray) -> tuple[float, float]:
    """(smallest, largest) scale factor of the projection over (a sample of) the points."""
    from pyproj import Proj

    ok = np.flatnonzero(np.isfinite(lonlat).all(axis=1))
    sample = ok[:: max(1, len(ok) // SCALE_SAMPLE)]
    k = np.asarray(Proj(crs).get_factors(lonlat[sample, 0], lonlat[sample, 1]).meridional_scale)
    k = k[np.isfinite(k)]
    return (float(k.min()), float(k.max())) if len(k) else (1.0, 1.0)


def geographic_points(points: np.ndarray, attributes: dict[str, np.ndarray], names: list[str],
                      explicit: bool, source: str = "the file"
                      ) -> tuple[np.ndarray, dict[str, np.ndarray], tuple, object]:
    """Project named longitude/latitude columns to metres: (points, attributes, notes, georef).

    Picked automatically, a third (height) column becomes the attribute 'altitude' and the
    footprint is 2D; named explicitly (`--columns lon,lat,alt`), it is z in metres (3D).
    Columns not named as geographic, or not in degrees, are returned as they are (with a note
    in the second case); a few rows out of range among degrees are a FileFormatError naming
    `source` and the row.
    """
    axes = geographic_axes(names)
    if axes is None:
        return points, attributes, (), None
    lonlat = points[:, list(axes)]
    refuse_stray_rows(lonlat, source)
    height = None if points.shape[1] == 2 else ("z" if explicit else "altitude")
    columns = tuple(names[i] for i in axes) + tuple(names[2:3])
    result = localize(lonlat, columns, height)
    if isinstance(result, str):
        return points, attributes, (f"columns {', '.join(names[:2])} read as plain numbers, "
                                    f"not projected: {result}",), None
    xy, georef = result
    attributes = dict(attributes)
    if height == "altitude":
        attributes["altitude"] = points[:, 2].copy()
        return xy, attributes, (), georef
    if height == "z":
        return np.column_stack([xy, points[:, 2]]), attributes, (), georef
    return xy, attributes, (), georef

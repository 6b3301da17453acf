"""Georeference of points read from longitude/latitude: the local projection to metres and back.

Geographic input (WGS 84 degrees) is built in a local conformal projection so that alpha is a
length in metres; exports go back to longitude/latitude through the same projection, and
areas and lengths of 2D shapes are measured on the WGS 84 ellipsoid (pyproj.Geod).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

WGS84 = "EPSG:4326"
WGS84_NAME = "WGS 84 longitude/latitude in degrees (EPSG:4326)"


@dataclass(frozen=True)
class Georef:
    """How geographic input became local metres: the projection, named and as PROJ text.

    `crs` is anything pyproj.CRS accepts ('EPSG:32633' or a PROJ string); `columns` are the
    source columns (longitude, latitude[, height]); `height` says what became of a height
    column: 'z' (3D, metres as given), an attribute name, or None (no height column);
    `scale` is the (smallest, largest) scale factor of the projection over the points;
    `centre_lon` the longitude of the data's centre (longitudes are unwrapped around it).
    """

    crs: str
    name: str
    columns: tuple[str, ...]
    height: str | None = None
    scale: tuple[float, float] = (1.0, 1.0)
    centre_lon: float = 0.0

    def _transformer(self, inverse: bool):
        """A fresh pyproj Transformer (they are not shared between threads)."""
        from pyproj import Transformer

        src, dst = (self.crs, WGS84) if inverse else (WGS84, self.crs)
        return Transformer.from_crs(src, dst, always_xy=True)

    def to_metres(self, lonlat: np.ndarray) -> np.ndarray:
        """(n, 2) float64 projected x, y in metres of (n, 2) longitude/latitude degrees."""
        lonlat = np.asarray(lonlat, dtype=np.float64).reshape(-1, 2)
        x, y = self._transformer(False).transform(lonlat[:, 0], lonlat[:, 1])
        return np.column_stack([x, y])

    def to_lonlat(self, xy: np.ndarray) -> np.ndarray:
        """(n, 2) float64 longitude/latitude degrees of (n, 2) projected metres; longitudes
        within 180 degrees of the data's centre (so may pass +-180 across the antimeridian)."""
        xy = np.asarray(xy, dtype=np.float64).reshape(-1, 2)
        lon, lat = self._transformer(True).transform(xy[:, 0], xy[:, 1])
        lon = self.centre_lon + (np.asarray(lon) - self.centre_lon + 180.0) % 360.0 - 180.0
        return np.column_stack([lon, lat])

    def line(self) -> str:
        """One line for the load report."""
        height = {None: "", "z": "; height as z in metres"}.get(
            self.height, f"; height kept as attribute {self.height!r}")
        return (f"{self.name}, metres, scale {self.scale[0]:.5g}..{self.scale[1]:.5g}, from "
                f"columns {', '.join(self.columns)} ({WGS84_NAME}){height}")

    def to_dict(self) -> dict:
        """JSON-ready description (load report, export metadata)."""
        return {"projection": self.name, "crs": self.crs, "units": "m", "source_crs": WGS84,
                "columns": list(self.columns), "height": self.height,
                "scale": list(self.scale), "centre_lon": self.centre_lon}


def geodesic_area_perimeter(geometry) -> tuple[float, float]:
    """(area m^2, perimeter m) of a shapely geometry in longitude/latitude, on WGS 84."""
    from pyproj import Geod

    area, perimeter = Geod(ellps="WGS84").geometry_area_perimeter(geometry)
    return abs(float(area)), float(perimeter)


def geodesic_length(geometry) -> float:
    """Length in metres of a shapely (multi)line in longitude/latitude, on WGS 84."""
    from pyproj import Geod

    return float(Geod(ellps="WGS84").geometry_length(geometry))

"""Alpha Scoop core: the alpha-shape computation over numpy arrays (no Qt, no VTK, no pyvista).

`AlphaComplex.from_points(points)` builds the Delaunay triangulation and the interval table
once (core/pipeline.py); `ac.shape(alpha)` and the other queries are then cheap lookups in its
TableIndex (core/query/index.py). Alpha is a radius (or `alpha2=`, its square).
"""

from core.complex import EXTERIOR, INTERIOR, REGULAR, SINGULAR, AlphaComplex
from core.errors import AlphaScoopError, Cancelled, FileFormatError, InputError
from core.pipeline import BuildInfo
from core.query.shape import AlphaShape

__all__ = [
    "EXTERIOR",
    "INTERIOR",
    "REGULAR",
    "SINGULAR",
    "AlphaComplex",
    "AlphaScoopError",
    "AlphaShape",
    "BuildInfo",
    "Cancelled",
    "FileFormatError",
    "InputError",
]

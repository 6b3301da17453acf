"""Alpha Scoop core: pure numpy/scipy alpha-shape computation (no Qt, no VTK).

`AlphaComplex.from_points(points)` builds the Delaunay triangulation and the interval table
once (core/build.py); `ac.shape(alpha)` and the other queries are then cheap lookups in its
TableIndex (core/index.py). Alpha is a radius (or `alpha2=`, its square).
"""

from .build import BuildInfo
from .complex import EXTERIOR, INTERIOR, REGULAR, SINGULAR, AlphaComplex
from .errors import AlphaScoopError, Cancelled, FileFormatError, InputError
from .shape import AlphaShape

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

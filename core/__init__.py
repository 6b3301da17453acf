"""Alpha Scoop core: pure numpy/scipy alpha-shape computation (no Qt, no VTK).

`AlphaComplex.from_points(points)` builds the Delaunay triangulation and the interval table
once; `ac.shape(alpha)` and the other queries are then cheap. Alpha is always a radius.
"""

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
    "Cancelled",
    "FileFormatError",
    "InputError",
]

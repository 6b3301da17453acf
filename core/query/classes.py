"""The four classes of a simplex at one alpha (Edelsbrunner-Mücke): values and names."""

from __future__ import annotations

#: Values of `AlphaComplex.classify`: not in the complex, in it but face of no cell of it,
#: on the boundary of the shape, inside it.
EXTERIOR, SINGULAR, REGULAR, INTERIOR = 0, 1, 2, 3
#: Their names, by value (the columns of `Signatures.counts`).
CLASSES = ("exterior", "singular", "regular", "interior")

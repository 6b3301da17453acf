"""Geometric primitives: circumspheres, orthospheres, exact and filtered predicates, local
neighbourhoods, georeference.
"""

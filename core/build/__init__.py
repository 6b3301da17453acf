"""From points to an interval table: input checks, the triangulation, its certification and repair,
the table's passes.
"""

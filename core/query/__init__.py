"""Queries on a built table: its frozen index, alpha checks, the shape at one alpha, the moving
cursor, one simplex's spoon, point location.
"""

"""Exact alpha shapes at one alpha, tile by tile: scans bigger than memory.

Placeholder docstring; the argument is written below.
"""

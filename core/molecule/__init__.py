"""Molecules as weighted alpha complexes: exact area and volume of the union of balls,
per-atom exposed area and cavities (`analysis.measure_molecule`)."""

"""Topology over the filtration: union-find forests, Betti numbers, components, persistence,
signatures, and the alphas they suggest (opening, optimal, stable ranges).
"""

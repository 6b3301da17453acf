"""core/geometry/neighbourhood.py: the closed-form smallest eigenvectors of the PCA normals against
LAPACK's eigh, on random, flat (surface-like) and degenerate covariances; the orientation
graph against scipy's own COO to CSR conversion."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.sparse import coo_matrix

from core.geometry.neighbourhood import least_axes, orientation_graph


def _covariances(kind: str) -> np.ndarray:
    rng = np.random.default_rng(0)
    if kind == "flat":  # neighbourhoods of a surface at random orientations
        x = rng.normal(size=(400, 17, 3)) * np.array([1.0, 0.7, 1e-3])
        x = x @ np.linalg.qr(rng.normal(size=(400, 3, 3)))[0]
        x -= x.mean(axis=1, keepdims=True)
        return x.transpose(0, 2, 1) @ x
    if kind == "random":
        a = rng.normal(size=(400, 3, 3))
        return a @ a.transpose(0, 2, 1)
    return np.stack([np.zeros((3, 3)), np.eye(3), np.diag([1.0, 1.0, 0.0]),  # degenerate:
                     np.diag([0.0, 1.0, 1.0]), np.diag([2.0, 0.0, 0.0]),     # repeated or
                     np.full((3, 3), 1.0)])                                  # zero values


@pytest.mark.parametrize("kind", ["flat", "random", "degenerate"])
def test_least_axes_are_the_smallest_eigenvectors(kind):
    cov = _covariances(kind)
    axes = least_axes(cov)
    lowest = np.linalg.eigvalsh(cov)[:, 0]
    np.testing.assert_allclose(np.linalg.norm(axes, axis=1), 1.0, atol=1e-12)
    residual = np.einsum("nij,nj->ni", cov, axes) - lowest[:, None] * axes
    scale = np.abs(cov).max(axis=(1, 2))[:, None] + 1.0
    assert (np.abs(residual) <= 1e-10 * scale).all()
    if kind == "flat":  # a simple lowest eigenvalue: the same axis as eigh, up to sign
        want = np.linalg.eigh(cov)[1][:, :, 0]
        np.testing.assert_allclose(np.abs(np.einsum("nd,nd->n", axes, want)), 1.0, atol=1e-12)


def test_least_axes_in_2d_use_eigh():
    cov = np.array([[[2.0, 0.0], [0.0, 1.0]], [[1.0, 1.0], [1.0, 1.0]]])
    axes = least_axes(cov)
    np.testing.assert_allclose(np.abs(axes), np.sqrt([[0.0, 1.0], [0.5, 0.5]]), atol=1e-12)


@pytest.mark.parametrize("dim", [2, 3])
def test_orientation_graph_is_the_canonical_csr_of_the_neighbour_graph(dim):
    """Built column by column, the graph is the same CSR matrix, array for array, as the
    COO matrix of every (point, neighbour) edge converted by scipy; so the spanning tree,
    whose ties follow the order of its data, is the same."""
    rng = np.random.default_rng(dim)
    normals = rng.normal(size=(300, dim))
    normals[:40] = normals[0]  # exactly parallel normals: equal weights, tied edges
    normals /= np.linalg.norm(normals, axis=1)[:, None]
    ids = np.argsort(rng.uniform(size=(300, 300)), axis=1)[:, :8]
    m, k = ids.shape
    rows, cols = np.repeat(np.arange(m), k), ids.ravel()
    dots = np.einsum("md,md->m", normals[rows], normals[cols])
    want = coo_matrix((1.0 - np.abs(dots) + 1e-9, (rows, cols)), shape=(m, m)).tocsr()
    got = orientation_graph(normals, ids)
    for name in ("data", "indices", "indptr"):
        assert np.array_equal(getattr(got, name), getattr(want, name)), name
        assert getattr(got, name).dtype == getattr(want, name).dtype

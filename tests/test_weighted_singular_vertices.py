"""Weighted vertices enter at -w, so their level is not sorted by enter: the shape's and the
cursor's SINGULAR sets must still equal classify() at every alpha² (negative ones too)."""

import numpy as np
import pytest

from core import AlphaComplex


@pytest.mark.parametrize("dim", [2, 3])
def test_singular_sets_equal_classify_at_every_alpha2(dim):
    rng = np.random.default_rng(3)
    points = rng.uniform(size=(60, dim))
    ac = AlphaComplex.from_points(points, weights=rng.uniform(0, 0.02, size=60))
    assert not np.all(np.diff(ac.intervals_sq(0)[:, 0]) >= 0)  # the case this guards
    cursor = ac.cursor()
    values = np.concatenate([ac.spectrum_sq(), [-0.005, 0.0]])
    for alpha2 in np.concatenate([values, values[::-3]]):
        shape, moved = ac.shape(alpha2=alpha2), cursor.move(alpha2=alpha2)
        for k in range(dim):
            expected = ac.simplices(k)[ac.classify(alpha2=alpha2, k=k) == 1]
            for got in (shape.singular(k), moved.singular(k)):
                assert sorted(map(tuple, got)) == sorted(map(tuple, expected)), (alpha2, k)

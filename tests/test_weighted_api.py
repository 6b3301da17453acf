"""The weighted API: alpha / alpha2 on every query, squared views, input checks, storage and
cache keeping the weights."""

from __future__ import annotations

import numpy as np
import pytest

from core import AlphaComplex
from core.cache import entry_path, load_cached
from core.errors import InputError
from core.obtain import obtain


@pytest.fixture(scope="module")
def weighted() -> tuple[AlphaComplex, np.ndarray, np.ndarray]:
    rng = np.random.default_rng(21)
    pts = rng.random((400, 3))
    w = rng.uniform(0.0, 0.02, 400)
    return AlphaComplex.from_points(pts, weights=w), pts, w


def test_weights_and_squared_views(weighted) -> None:
    ac = weighted[0]
    assert ac.weights.shape == (len(ac.points),) and not ac.weights.flags.writeable
    assert (ac.input_index < 0).any()
    for k in range(ac.dim + 1):
        iv, sq = ac.intervals(k), ac.intervals_sq(k)
        np.testing.assert_array_equal(sq, np.sign(iv) * iv * iv)
    spectrum = ac.spectrum_sq()
    assert spectrum[0] < 0 and (np.diff(spectrum) > 0).all()
    assert spectrum[0] == ac.intervals_sq(0)[:, 0].min()


@pytest.mark.parametrize("value", [-0.01, -1e-4, 0.0, 2e-3, 0.05])
def test_alpha2_queries_agree_with_the_squared_table(weighted, value: float) -> None:
    ac, pts, _ = weighted
    for k in range(ac.dim + 1):
        expected = (ac.intervals_sq(k) <= value).sum(axis=1)
        np.testing.assert_array_equal(ac.classify(alpha2=value, k=k), expected)
    shape = ac.shape(alpha2=value)
    assert shape.alpha2 == pytest.approx(value, rel=1e-15, abs=0)
    assert len(shape.cells) == int((ac.intervals_sq(ac.dim)[:, 0] <= value).sum())
    moved = ac.cursor().move(alpha2=value)
    assert np.array_equal(np.sort(moved.regular_facet_ids), np.sort(shape.regular_facet_ids))
    assert ac.contains(pts[:50], alpha2=value).sum() <= 50
    if value >= 0:
        r = float(np.sqrt(value))
        assert ac.betti(alpha2=value) == ac.betti(r)
        assert np.array_equal(ac.classify(r, 1), ac.classify(alpha2=value, k=1))
        assert np.array_equal(ac.contains(pts, r), ac.contains(pts, alpha2=value))


def test_ambiguous_or_malformed_alpha_is_refused(weighted) -> None:
    ac, pts, _ = weighted
    calls = [lambda **kw: ac.shape(**kw), lambda **kw: ac.betti(**kw),
             lambda **kw: ac.classify(k=1, **kw), lambda **kw: ac.cursor().move(**kw),
             lambda **kw: ac.contains(pts[:3], **kw)]
    for call in calls:
        with pytest.raises(InputError, match="exactly one"):
            call(alpha=0.1, alpha2=0.01)
        with pytest.raises(InputError, match="exactly one"):
            call()
        with pytest.raises(InputError, match="alpha2 must be a number"):
            call(alpha2="x")


def test_a_negative_alpha_is_the_signed_radius_of_a_negative_alpha2(weighted) -> None:
    """A weighted table takes the signed radius optimal_alpha() may return: alpha -0.1 is
    alpha2 -0.01."""
    ac, _, _ = weighted
    for k in range(ac.dim + 1):
        np.testing.assert_array_equal(ac.classify(k=k, alpha=-0.1), ac.classify(k=k, alpha2=-0.01))


def test_optimal_suggestions_and_persistence_on_a_weighted_table(weighted) -> None:
    ac, _, _ = weighted
    best = ac.optimal_alpha()
    assert ac.optimal_alpha2() == pytest.approx(np.sign(best) * best * best)
    assert ac.signatures().solid_components[ac.signatures().index(best)] <= 1
    for r in ac.suggest_alphas(3):
        assert r.low2 < r.alpha2 < r.high2
        assert ac.betti(alpha2=r.alpha2) == r.betti
    births = ac.persistence().diagram(0)[:, 0]
    assert births.min() == ac.intervals(0)[:, 0].min()


def test_classic_complex_takes_alpha2_too() -> None:
    pts = np.random.default_rng(2).random((200, 2))
    ac = AlphaComplex.from_points(pts)
    assert ac.weights is None
    assert ac.betti(alpha2=0.0025) == ac.betti(0.05)
    assert ac.classify(alpha2=-1.0, k=0).max() == 0  # below zero radius: nothing in
    assert np.array_equal(ac.intervals_sq(2), ac.intervals(2) ** 2)


@pytest.mark.parametrize("bad", [np.ones(3), np.ones((400, 2)), np.full(400, np.nan), "w"])
def test_bad_weights_are_input_errors(bad) -> None:
    pts = np.random.default_rng(2).random((400, 2))
    with pytest.raises(InputError, match="weight"):
        AlphaComplex.from_points(pts, weights=bad)


def test_weights_and_alpha_modes_do_not_combine() -> None:
    pts = np.random.default_rng(2).random((100, 2))
    with pytest.raises(InputError, match="weights cannot be combined"):
        AlphaComplex.from_points(pts, weights=np.full(100, 1e-4), density=4)


def test_save_and_load_keep_weights(weighted, tmp_path) -> None:
    ac, _, _ = weighted
    ac.signatures()
    ac.save(tmp_path / "w.npz")
    back = AlphaComplex.load(tmp_path / "w.npz")
    np.testing.assert_array_equal(back.weights, ac.weights)
    np.testing.assert_array_equal(back.input_index, ac.input_index)
    for k in range(ac.dim + 1):
        np.testing.assert_array_equal(back.intervals_sq(k), ac.intervals_sq(k))
    np.testing.assert_array_equal(back.signatures().betti, ac.signatures().betti)
    assert back.betti(alpha2=-1e-3) == ac.betti(alpha2=-1e-3)


def test_a_table_without_weights_loads_as_classic(tmp_path) -> None:
    pts = np.random.default_rng(4).random((100, 2))
    ac = AlphaComplex.from_points(pts)
    ac.save(tmp_path / "c.npz")
    with np.load(tmp_path / "c.npz") as data:
        assert "weights" not in data.files  # the layout of tables saved before weights
    assert AlphaComplex.load(tmp_path / "c.npz").weights is None


def test_cache_key_includes_weights(tmp_path, monkeypatch) -> None:
    monkeypatch.setenv("ALPHASCOOP_CACHE_DIR", str(tmp_path))
    pts = np.random.default_rng(6).random((150, 2))
    w = np.random.default_rng(7).uniform(0, 1e-3, 150)
    assert entry_path(pts) != entry_path(pts, weights=w) != entry_path(pts, weights=2 * w)
    built = obtain(pts, weights=w).complex
    assert entry_path(pts, weights=w).is_file() and not entry_path(pts).is_file()
    cached = load_cached(pts, weights=w)
    np.testing.assert_array_equal(cached.weights, built.weights)
    assert load_cached(pts) is None
    assert obtain(pts).complex.weights is None

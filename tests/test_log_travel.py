"""The slider's log-alpha travel and the alpha history (no Qt)."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from reference import data_dir, needs_data

from app.history import AlphaHistory
from app.log_travel import LOW_QUANTILE, PAGE_FACTOR, TRAVEL, LogTravel, sorted_quantile
from core import AlphaComplex

DATA = data_dir()


@pytest.fixture(scope="module")
def spectrum() -> np.ndarray:
    return AlphaComplex.from_points(np.random.default_rng(3).random((400, 3))).spectrum()


def test_positions_rise_with_alpha_from_end_to_end(spectrum) -> None:
    travel = LogTravel(spectrum)
    positions = np.array([travel.position(i) for i in range(len(spectrum))])
    assert positions[0] == 0 and positions[-1] == TRAVEL
    assert np.all(np.diff(positions) >= 0)


def test_travel_is_linear_in_log_alpha(spectrum) -> None:
    """Equal ratios of alpha are equal distances on the slider (inside the travel's ends)."""
    travel = LogTravel(spectrum)
    low, high = np.exp(travel.log_low), np.exp(travel.log_high)
    inside = np.flatnonzero((spectrum > low) & (spectrum < high))
    a, b = inside[len(inside) // 4], inside[len(inside) // 2]
    per_log = TRAVEL / (travel.log_high - travel.log_low)
    expected = per_log * np.log(spectrum[b] / spectrum[a])
    assert travel.position(b) - travel.position(a) == pytest.approx(expected, abs=1.0)


def test_a_position_shows_the_critical_value_at_or_below_it(spectrum) -> None:
    travel = LogTravel(spectrum)
    for position in (1, 100, 2500, 5000, 9999):
        index = travel.index_at(position)
        assert travel.position(index) <= position
        if index + 1 < len(spectrum) - 1:
            assert travel.position(index + 1) >= position


def test_page_moves_by_the_factor_snapped_and_at_least_one_value(spectrum) -> None:
    travel = LogTravel(spectrum)
    for index in (5, len(spectrum) // 2, len(spectrum) - 3):
        up, down = travel.page(index, True), travel.page(index, False)
        assert up > index and down < index
        alpha = spectrum[index]
        assert up == index + 1 or spectrum[up] <= alpha * PAGE_FACTOR < spectrum[up + 1]
        assert spectrum[down] <= alpha / PAGE_FACTOR or down == index - 1
    assert travel.page(0, False) == 0 and travel.page(len(spectrum) - 1, True) == len(spectrum) - 1


@needs_data
@pytest.mark.parametrize("name", ["milk.pcd", "bunny.ply", "us_airports.csv"])
def test_page_up_from_the_opening_never_reaches_the_hull(name) -> None:
    """On real scans the opening alpha sits well inside the travel, and a PageUp from it stays
    far below the convex hull."""
    from core.io import read_points
    from core.obtain import obtain

    ps = read_points(DATA / name)
    ac = obtain(ps.points, weights=ps.weights, signatures=True).complex
    spectrum = ac.spectrum()
    travel = LogTravel(spectrum, reach=ac.optimal_alpha())
    opening = int(np.searchsorted(spectrum, ac.default_alpha(), side="right")) - 1
    assert 0.05 < travel.position(opening) / TRAVEL < 0.8
    up = travel.page(opening, True)
    assert up < len(spectrum) - 1 and spectrum[up] <= PAGE_FACTOR * spectrum[opening]


def test_history_goes_back_and_forward() -> None:
    history = AlphaHistory(merge_seconds=0.0)
    history.reset(10)
    for index in (20, 30):
        history.visit(index)
    assert history.back() == 20 and history.back() == 10 and history.back() is None
    assert history.forward() == 20
    history.visit(99)  # a new visit drops the forward entries
    assert not history.can_forward() and history.entries == [10, 20, 99]


def test_history_merges_quick_successive_visits() -> None:
    """A drag or a held key is one visit: moves within merge_seconds replace each other."""
    now = [0.0]
    history = AlphaHistory(merge_seconds=0.5, clock=lambda: now[0])
    history.reset(1)
    for index, time in ((2, 1.0), (3, 1.1), (4, 1.2), (5, 3.0)):
        now[0] = time
        history.visit(index)
    assert history.entries == [1, 4, 5]


@given(st.lists(st.floats(-10.0, 1e6, allow_nan=False), min_size=1, max_size=60),
       st.sampled_from([0.0, LOW_QUANTILE, 0.37, 0.5, 0.999, 1.0]))
def test_sorted_quantile_is_numpys_quantile(values, q) -> None:
    """The travel's ends read off the sorted spectrum equal numpy's (sorting) quantile."""
    values = np.sort(np.array(values))
    assert sorted_quantile(values, q) == pytest.approx(float(np.quantile(values, q)),
                                                       rel=1e-12, abs=1e-9)


def test_travel_ends_are_quantiles_of_the_positive_alphas(spectrum) -> None:
    travel = LogTravel(spectrum)
    positive = spectrum[spectrum > 0]
    assert np.exp(travel.log_low) == pytest.approx(np.quantile(positive, LOW_QUANTILE), rel=1e-12)

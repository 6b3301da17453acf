"""Tests of the window-step benchmark's harness on tiny inputs (no window, no timed bounds)."""

from __future__ import annotations

import pytest
from bench_window_step import goal_figures, table
from isolated_results import results_elsewhere  # noqa: F401 (autouse fixture)
from window_step import PartTimer, percentile, summary


def test_percentile_interpolates_between_ranks():
    assert percentile([1.0], 95) == 1.0
    assert percentile([0.0, 10.0], 50) == 5.0
    assert percentile(list(range(101)), 95) == pytest.approx(95.0)


def test_nested_parts_count_their_own_time_once():
    timer = PartTimer()
    inner = timer._wrap(lambda: sum(range(20_000)), "cursor")
    outer = timer._wrap(lambda: [inner() for _ in range(3)], "scene arrays")
    outer()
    assert set(timer.seconds) == {"cursor", "scene arrays"}
    assert timer.seconds["cursor"] > 0 and timer.seconds["scene arrays"] >= 0
    timer.reset()
    assert not timer.seconds and timer.renders == 0


def rows(seconds, bare):
    return [{"seconds": s, "bare": bare, "parts": {"render": s / 2, "plots": s / 10},
             "renders": 1, "changed": True} for s in seconds]


def test_summary_and_goal_figures_from_steps():
    scan = summary(rows([0.2, 0.3, 0.25, 0.9], bare=0.2))
    assert scan["median"] == pytest.approx(0.275) and scan["p95"] > 0.8
    assert scan["shares"]["render"] == pytest.approx(0.5)
    assert sum(scan["shares"].values()) == pytest.approx(1.0)
    protein = summary(rows([0.3, 0.3], bare=0.25))
    results = {"scan40k": {"file": "a.ply", "kinds": {"arrow": scan}},
               "protein": {"file": "p.pdb", "kinds": {"arrow": protein}},
               "scan200k": {"file": "b.npy", "kinds": {"arrow": scan},
                            "drag": {"fps": 25.0, "release_seconds": 0.4}}}
    figures = {f.name: f for f in goal_figures(results)}
    assert figures["window_step.scan40k.median"].anchor_value == pytest.approx(0.43)
    assert figures["window_step.scan40k.median"].met  # 0.275 <= 2 x 0.2 + 0.03
    assert not figures["window_step.scan40k.p95"].met  # 0.8+ > 3 x 0.2 + 0.05
    assert figures["window_step.protein_vs_scan40k"].ratio == pytest.approx(0.3 / 0.275)
    assert figures["window_step.drag_fps_200k"].met
    assert not figures["window_step.release_200k"].met  # 0.4 s > 0.3 s
    assert len(table(results)["rows"]) == 3

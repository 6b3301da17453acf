"""Messages say what is wrong, and what the API returns it accepts: a radius too large to
square is no 'NaN or infinite', '--alpha2 -1e-3' parses, the optimum of a weighted set
below zero is a valid alpha, no RuntimeWarning leaves the core, and --probe on points or a
density larger than the points are said."""

from __future__ import annotations

import json
import warnings
from pathlib import Path

import numpy as np
import pytest

from app.cli import main
from core import AlphaComplex
from core.errors import FileFormatError, InputError
from core.io import read_points
from core.topology.components import solid_labels

DATA = Path(__file__).parent / "data"
SCAN = DATA / "corpus" / "pcd" / "pcl_bun01.pcd"
LIGAND = DATA / "molecules" / "gemmi_HEM.pdb"


@pytest.fixture(autouse=True)
def cache(tmp_path, monkeypatch):
    monkeypatch.setenv("ALPHASCOOP_CACHE_DIR", str(tmp_path / "cache"))


def _run(capsys, *argv) -> tuple[int, str, str]:
    code = main([str(a) for a in argv])
    out, err = capsys.readouterr()
    return code, out, err


@pytest.mark.parametrize("option", ["--probe", "--radius-add"])
def test_a_radius_too_large_to_square_is_named_so(capsys, tmp_path, option):
    target = LIGAND if option == "--probe" else tmp_path / "balls.csv"
    if option == "--radius-add":
        points = read_points(SCAN).points
        np.savetxt(target, np.column_stack([points, np.full(len(points), 0.01)]),
                   delimiter=",", header="x,y,z,radius", comments="")
    code, _, err = _run(capsys, "info", target, option, "1e200")
    assert code == 2 and "too large" in err and "NaN or infinite" not in err


def test_a_radius_column_too_large_to_square(tmp_path):
    points = read_points(SCAN).points
    radii = np.full(len(points), 0.01)
    radii[5] = 1e200
    path = tmp_path / "balls.csv"
    np.savetxt(path, np.column_stack([points, radii]), delimiter=",", header="x,y,z,radius",
               comments="")
    with pytest.raises(FileFormatError, match=r"radius 1e\+200 .*row 5\) is too large"):
        read_points(path, radius="radius")


@pytest.mark.parametrize("argv", [["--alpha2", "-1e-3"], ["--alpha2=-1e-3"],
                                  ["--alpha2", "-0.001"]])
def test_negative_squared_alpha_with_an_exponent_parses(capsys, argv):
    code, out, err = _run(capsys, "info", SCAN, "--json", *argv)
    assert code == 0, err
    assert json.loads(out)["alpha2"] == pytest.approx(-1e-3)


def _overlapping_balls() -> AlphaComplex:
    """The corpus scan's points as balls so large that their union closes below zero."""
    points = read_points(SCAN).points
    radius = 2.0 * AlphaComplex.from_points(points).optimal_alpha()  # twice the classic one
    return AlphaComplex.from_points(points, weights=np.full(len(points), radius**2))


def test_what_optimal_alpha_returns_below_zero_is_accepted():
    ac = _overlapping_balls()
    optimal = ac.optimal_alpha()
    assert optimal < 0
    shape = ac.shape(optimal)
    want = ac.shape(alpha2=ac.optimal_alpha2())
    assert shape.alpha == want.alpha and shape.measure == want.measure
    assert ac.betti(optimal) == ac.betti(alpha2=ac.optimal_alpha2())
    np.testing.assert_array_equal(ac.classify(optimal, k=1),
                                  ac.classify(alpha2=ac.optimal_alpha2(), k=1))
    assert ac.cursor().move(optimal).measure == want.measure
    assert len(solid_labels(ac, optimal)) == int(np.sum(ac.intervals(ac.dim)[:, 0] <= optimal))
    classic = AlphaComplex.from_points(read_points(SCAN).points)
    with pytest.raises(InputError, match="radius and must be >= 0"):
        classic.shape(-0.5)  # a classic table has no value below zero


def test_huge_weights_are_refused_not_overflowed():
    points = read_points(SCAN).points
    weights = np.full(len(points), 1e-6)
    weights[3] = 1e300
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        with pytest.raises(InputError, match="out of proportion"):
            AlphaComplex.from_points(points, weights=weights)


def test_subnormal_coordinates_build_without_warnings():
    points = read_points(SCAN).points
    tiny = points / np.abs(points).max() * 1e-310
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        ac = AlphaComplex.from_points(tiny)
    assert ac.counts()[0] == len(np.unique(tiny, axis=0))
    assert np.all(np.isfinite(ac.spectrum()))


def test_probe_on_points_and_a_clamped_density_are_said(capsys):
    code, _, err = _run(capsys, "info", SCAN, "--probe", "2")
    assert code == 2 and "--probe applies to molecule files" in err
    code, out, err = _run(capsys, "info", SCAN, "--json", "--density", "1000")
    n = len(read_points(SCAN).points)
    assert code == 0 and f"--density 1000 asks for more neighbours than the {n:,}" in err
    assert json.loads(out)["build"]["density_neighbours"] == n - 1
    code, out, err = _run(capsys, "info", SCAN, "--json", "--density", "8")
    assert "neighbours than" not in err and json.loads(out)["build"]["density_neighbours"] == 0
    code, out, _ = _run(capsys, "info", LIGAND, "--json")
    assert code == 0 and json.loads(out)["molecule"]["probe"] == 1.4  # the default stays

"""Hand-made text files from the wild: each variant is read exactly or refused with a reason."""

from __future__ import annotations

import numpy as np
import pytest

from core.errors import FileFormatError
from core.io import read_points

PTS = np.array([[1.0, 2.0, 3.0], [4.5, 5.0, 6.0], [7.0, 8.25, 9.0], [1.5, 0.5, 2.0]])


def _rows(fmt: str, sep: str = " ") -> str:
    return "".join(fmt.format(sep.join(f"{v:g}" for v in p)) for p in PTS)


@pytest.mark.parametrize(("name", "text"), [
    ("bom.xyz", "\ufeff" + _rows("{}\n")),
    ("bom.csv", "\ufeff" + _rows("{}\n", ",")),
    ("trailing_delimiter.csv", _rows("{},\n", ",")),
    ("trailing_semicolon.csv", _rows("{};\n", ";")),
    ("trailing_comment.xyz", _rows("{} # scan 1\n")),
    ("trailing_comment.csv", _rows("{} # scan 1\n", ",")),
    ("trailing_tab.txt", _rows("{}\t\n", "\t")),
    ("crlf_trailing_tab.txt", _rows("{}\t\r\n", "\t")),
])
def test_headerless_first_row_is_kept(tmp_path, name, text):
    (tmp_path / name).write_bytes(text.encode("utf-8"))
    ps = read_points(tmp_path / name)
    np.testing.assert_array_equal(ps.points, PTS)


def _comma(text: str) -> str:
    return text.replace(".", ",")


@pytest.mark.parametrize(("name", "text"), [
    ("spaces.xyz", _comma(_rows("{}\n"))),  # '1 2 3' / '4,5 5 6' ...
    ("semicolons.csv", _comma(_rows("{}\n", ";"))),
    ("header.csv", "X;Y;Z\n" + _comma(_rows("{}\n", ";"))),
    ("tabs.txt", _comma(_rows("{}\n", "\t"))),
])
def test_decimal_commas_read_when_unambiguous(tmp_path, name, text):
    (tmp_path / name).write_text(text)
    ps = read_points(tmp_path / name)
    np.testing.assert_array_equal(ps.points, PTS)
    assert "decimal commas read as decimal points" in ps.report.notes


def test_decimal_commas_example(tmp_path):
    (tmp_path / "p.xyz").write_text("1,5 2,25 3,0\n4,0 5,5 6,125\n")
    np.testing.assert_array_equal(read_points(tmp_path / "p.xyz").points,
                                  [[1.5, 2.25, 3.0], [4.0, 5.5, 6.125]])


@pytest.mark.parametrize(("text", "message"), [
    ("1,5 2.25 3,0\n4,0 5,5 6,1\n", "both as a decimal separator"),
    ("1,234.5 2,345.25 3.0\n4.0 5.0 6.0\n", "thousands separators"),
    ("1.234,5;2,0;3,0\n4,0;5,0;6,0\n", "thousands separators"),
    ('"1,234.5","2.0","3.0"\n"4.0","5.0","6.0"\n', "thousands separators"),
])
def test_ambiguous_numbers_refused_with_reason(tmp_path, text, message):
    (tmp_path / "p.csv").write_text(text)
    with pytest.raises(FileFormatError, match=message):
        read_points(tmp_path / "p.csv")


def test_comma_csv_with_spaces_is_not_decimal_commas(tmp_path):
    (tmp_path / "p.csv").write_text("1, 5, 2\n3, 4, 5\n0.5, 1.25, 7\n")
    ps = read_points(tmp_path / "p.csv")
    np.testing.assert_array_equal(ps.points, [[1, 5, 2], [3, 4, 5], [0.5, 1.25, 7]])
    assert not any("decimal commas" in n for n in ps.report.notes)


def test_two_column_csv_is_not_thousands(tmp_path):
    (tmp_path / "p.csv").write_text("1,234.5\n2,0.5\n3,1.5\n")
    np.testing.assert_array_equal(read_points(tmp_path / "p.csv").points,
                                  [[1, 234.5], [2, 0.5], [3, 1.5]])


@pytest.mark.parametrize("sep", [" ", ","])
def test_fortran_d_exponents(tmp_path, sep):
    text = sep.join(["1.0D+00", "2.5d-01", "3.0D2"]) + "\n" + sep.join(["4D0", "5.0", "6.0"])
    (tmp_path / "p.txt").write_text(text + "\n")
    ps = read_points(tmp_path / "p.txt")
    np.testing.assert_array_equal(ps.points, [[1.0, 0.25, 300.0], [4.0, 5.0, 6.0]])
    assert "Fortran 'D' exponents read" in ps.report.notes


def test_pts_with_several_scans(tmp_path):
    rng = np.random.default_rng(4)
    scans = [rng.uniform(size=(n, 3)).round(4) for n in (5, 3, 7)]
    text = "".join(f"{len(s)}\n" + "".join(f"{x} {y} {z} 10 1 2 3\n" for x, y, z in s)
                   for s in scans)
    (tmp_path / "multi.pts").write_text(text)
    ps = read_points(tmp_path / "multi.pts")
    np.testing.assert_array_equal(ps.points, np.vstack(scans))
    assert "PTS: 3 scans, 15 points read" in ps.report.notes


def test_pts_count_that_disagrees_is_reported(tmp_path):
    (tmp_path / "short.pts").write_text("3\n1 2 3\n4 5 6\n2\n7 8 9\n")
    ps = read_points(tmp_path / "short.pts")
    assert len(ps.points) == 3
    assert "PTS: 2 scans, 3 points read (the count lines promise 5)" in ps.report.notes


def test_pts_with_missing_value_and_second_scan(tmp_path):
    (tmp_path / "gap.pts").write_text("2\n1 2 3\n4 nan 6\n1\n7 8 9\n")
    ps = read_points(tmp_path / "gap.pts")
    np.testing.assert_array_equal(ps.points, [[1, 2, 3], [7, 8, 9]])

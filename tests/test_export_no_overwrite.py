"""An export never replaces the file it was read from, whatever path names that file."""

from __future__ import annotations

import os

import numpy as np
import pytest

from app.cli import main
from core import AlphaComplex
from core.errors import InputError
from core.export import write_shape, write_table

# (input/output extension, extra CLI options): every format that is both read and written
CASES = [(".ply", []), (".stl", []), (".obj", []), (".off", []), (".glb", []), (".gltf", []),
         (".vtu", []), (".npz", ["--table"]), (".csv", ["--table"])]
FORMS = ("same", "dotdot", "symlink", "hardlink")


@pytest.fixture(autouse=True)
def cache(tmp_path, monkeypatch):
    """A private table cache per test."""
    monkeypatch.setenv("ALPHASCOOP_CACHE_DIR", str(tmp_path / "cache"))


@pytest.fixture(scope="module")
def ac():
    return AlphaComplex.from_points(np.random.default_rng(5).normal(size=(80, 3)))


def input_file(folder, ext: str, ac) -> os.PathLike:
    """A readable point file of `ext` in folder: an exported surface, table or point table."""
    path = folder / f"b{ext}"
    if ext in (".npz", ".csv"):
        write_table(ac, path) if ext == ".npz" else np.savetxt(path, ac.points, delimiter=",")
    else:
        write_shape(ac, 10.0, path)
    return path


def output_name(path, form: str):
    """Another name for the same file on disk."""
    if form == "same":
        return path
    if form == "dotdot":
        (path.parent / "sub").mkdir(exist_ok=True)
        return path.parent / "sub" / ".." / path.name
    other = path.parent / f"other{path.suffix}"
    (os.symlink if form == "symlink" else os.link)(path, other)
    return other


@pytest.mark.parametrize("form", FORMS)
@pytest.mark.parametrize(("ext", "options"), CASES)
def test_cli_refuses_to_write_over_its_input(capsys, tmp_path, ac, ext, options, form):
    source = input_file(tmp_path, ext, ac)
    before = source.read_bytes()
    target = output_name(source, form)
    code = main(["export", str(source), "-o", str(target), "--alpha", "1", *options])
    out, err = capsys.readouterr()
    assert code == 2 and out == "" and len(err.strip().splitlines()) == 1
    assert "input file" in err and "Traceback" not in err
    assert source.read_bytes() == before
    assert not (tmp_path / "cache").exists(), "refused before reading or building anything"


@pytest.mark.parametrize("form", FORMS)
@pytest.mark.parametrize("ext", [".ply", ".npz"])
def test_core_writers_refuse_their_source(tmp_path, ac, form, ext):
    source = input_file(tmp_path, ext, ac)
    before = source.read_bytes()
    target = output_name(source, form)
    with pytest.raises(InputError, match="input file"):
        if ext == ".npz":
            write_table(ac, target, source=source)
        else:
            write_shape(ac, 1.0, target, source=source, sidecar=True)
    assert source.read_bytes() == before
    assert sorted(p.name for p in tmp_path.iterdir() if p.is_file()) == sorted(
        {source.name, target.name}), "nothing else written (no sidecar, no temporary)"


def test_a_different_file_with_the_same_name_elsewhere_is_fine(capsys, tmp_path, ac):
    source = input_file(tmp_path, ".ply", ac)
    (tmp_path / "out").mkdir()
    target = tmp_path / "out" / "b.ply"
    target.write_bytes(b"old export")
    assert main(["export", str(source), "-o", str(target), "--alpha", "1"]) == 0
    assert target.read_bytes() != b"old export"

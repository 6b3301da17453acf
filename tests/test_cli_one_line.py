"""The command line on odd values: huge alphas export, and any error is one line on stderr."""

from __future__ import annotations

import json
import subprocess
import sys
import textwrap
from pathlib import Path

import numpy as np
import pytest

from app.cli import main

ROOT = Path(__file__).resolve().parents[1]


@pytest.fixture(autouse=True)
def cache(tmp_path, monkeypatch):
    monkeypatch.setenv("ALPHASCOOP_CACHE_DIR", str(tmp_path / "cache"))


def strict_json(text: str):
    """json.loads that refuses NaN and Infinity (RFC 8259)."""
    def refuse(name):
        raise ValueError(f"{name} is not JSON")
    return json.loads(text, parse_constant=refuse)


@pytest.mark.parametrize(("dim", "ext"), [(3, ".ply"), (3, ".stl"), (3, ".obj"), (3, ".off"),
                                          (3, ".vtp"), (3, ".glb"), (3, ".gltf"), (3, ".vtu"),
                                          (2, ".geojson"), (2, ".wkt"), (2, ".svg"), (2, ".csv")])
@pytest.mark.parametrize("alpha", ["1e200", "1.3e154", "1.7976931348623157e308"])
def test_huge_alpha_exports_the_hull(capsys, tmp_path, dim, ext, alpha):
    source = tmp_path / "p.xyz"
    np.savetxt(source, np.random.default_rng(dim).random((60, dim)))
    out = tmp_path / f"out{ext}"
    code = main(["export", str(source), "-o", str(out), "--alpha", alpha, "--sidecar"])
    stdout, err = capsys.readouterr()
    assert code == 0 and err == "" and stdout.startswith(f"wrote {out}")
    meta = strict_json(Path(f"{out}.json").read_text())
    assert meta["alpha"] == float(alpha)
    square = float(alpha) ** 2 if float(alpha) < 1.3407807929942596e154 else None
    assert meta["alpha_sq"] == square
    if ext in (".geojson", ".gltf"):
        strict_json(out.read_text())


def test_unexpected_error_is_one_line(capsys, tmp_path, monkeypatch):
    import core.io

    def broken(*args, **kwargs):
        raise TypeError("unsupported operand type(s) for +: 'int' and 'str'")

    monkeypatch.setattr(core.io, "read_points", broken)
    code = main(["info", str(tmp_path / "p.xyz")])
    out, err = capsys.readouterr()
    assert code == 1 and out == "" and len(err.splitlines()) == 1
    assert err.startswith("alphascoop: error: ") and "TypeError" in err


SCRIPT = """
import sys, warnings
import numpy as np
import core.io
from core.errors import FileFormatError

def noisy(path, **kwargs):
    np.float64(1e308) * np.float64(10.0)          # numpy: overflow encountered
    np.array([0.0]) / np.array([0.0])             # numpy: invalid value
    np.nanmean(np.array([np.nan]))                # warnings.warn: mean of empty slice
    warnings.warn("values look odd", RuntimeWarning)
    {ending}

core.io.read_points = noisy
from app.cli import main
sys.exit(main(["info", "whatever.xyz"]))
"""


@pytest.mark.parametrize("ending", ['raise FileFormatError(f"{path}: no finite points")',
                                    "raise ZeroDivisionError('division by zero')"])
def test_numpy_warnings_never_print_before_the_error_line(tmp_path, ending):
    script = textwrap.dedent(SCRIPT).replace("{ending}", ending)
    result = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                            cwd=ROOT, env={"PYTHONPATH": str(ROOT), "PATH": "/usr/bin:/bin",
                                           "ALPHASCOOP_CACHE_DIR": str(tmp_path)}, timeout=120)
    assert result.returncode == 1 and result.stdout == ""
    assert len(result.stderr.splitlines()) == 1, result.stderr
    assert result.stderr.startswith("alphascoop: error: ")


def test_pockets_of_a_file_that_is_no_molecule(capsys, tmp_path):
    """`export --pockets` on weighted points that are no molecule says so (it blamed the
    output's extension, even a right one)."""
    source = tmp_path / "balls.xyz"
    rng = np.random.default_rng(5)
    np.savetxt(source, np.column_stack([rng.random((40, 3)), rng.uniform(0.1, 0.2, 40)]),
               header="x y z radius", comments="")
    code = main(["export", str(source), "-o", str(tmp_path / "p.vtu"), "--pockets"])
    err = capsys.readouterr().err
    assert code == 2 and len(err.strip().splitlines()) == 1
    assert "--pockets needs a molecule file" in err and "balls.xyz" in err

"""A normal (non-editable) install works: the wheel built from the sources, installed into a
fresh venv, holds every module and the bundled files, and renders the sample from outside the
repository. No network: the build runs without isolation and the new venv borrows the test
venv's installed dependencies through a .pth line (only the wheel itself is installed)."""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
import sysconfig
import time
import zipfile
from pathlib import Path

import numpy as np
import pytest
from conftest import image_contrast
from PIL import Image

REPO = Path(__file__).resolve().parent.parent
BUILD_INPUTS = ("pyproject.toml", "README.md", "app", "core")
PACKAGES = ("app", "core")
ASSETS = {"app/assets/sample.ply", "app/assets/icon.svg"}
# geogram's regular triangulation, compiled by the wheel build (pyproject.toml's ext-modules)
NATIVE = {f"core/backends/_geogram{sysconfig.get_config_var('EXT_SUFFIX')}"}
NATIVE_LICENCE = "licenses/core/backends/native/geogram/LICENSE"  # in the .dist-info folder
SIZE = (320, 240)
MIN_CONTRAST = 10.0
MIN_SHAPE_FRACTION = 0.02  # of the pixels, away from the background colour
STEP_TIMEOUT_S = 120
POLL_S = 0.2


def outside_env(**extra: str) -> dict[str, str]:
    """The environment minus PYTHONPATH (nothing may point back at the repository)."""
    env = {name: value for name, value in os.environ.items() if name != "PYTHONPATH"}
    return env | extra


def run(args: list[str], cwd: Path) -> subprocess.CompletedProcess:
    """Run args in cwd outside the repository; fail the test on a non-zero exit."""
    done = subprocess.run(args, cwd=cwd, env=outside_env(), capture_output=True, text=True,
                          timeout=STEP_TIMEOUT_S)
    assert done.returncode == 0, f"{args[:4]} failed:\n{done.stdout}\n{done.stderr}"
    return done


def source_modules() -> set[str]:
    """Repo-relative paths of the .py files the wheel must ship (not the scripts in
    app/assets, the link to the top-level assets/ folder)."""
    return {path.relative_to(REPO).as_posix()
            for package in PACKAGES for path in (REPO / package).rglob("*.py")
            if "__pycache__" not in path.parts and path.parts[len(REPO.parts) + 1] != "assets"}


@pytest.fixture(scope="module")
def wheel(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """The wheel built (pip, no build isolation) from a copy of the build inputs."""
    root = tmp_path_factory.mktemp("wheel")
    source = root / "source"
    for name in BUILD_INPUTS:
        if (REPO / name).is_dir():
            shutil.copytree(REPO / name, source / name,  # the library compiled anew
                            ignore=shutil.ignore_patterns("__pycache__", "*.pyc", "*.so",
                                                          "*.pyd"))
        else:
            source.mkdir(exist_ok=True)
            shutil.copy2(REPO / name, source / name)
    run([sys.executable, "-m", "pip", "wheel", "--no-deps", "--no-build-isolation",
         "--no-index", "-q", "-w", str(root / "dist"), str(source)], cwd=root)
    (built,) = (root / "dist").glob("alphascoop-*.whl")
    return built


@pytest.fixture(scope="module")
def venv(wheel: Path, tmp_path_factory: pytest.TempPathFactory) -> Path:
    """A fresh venv with the wheel installed and the test venv's site-packages on its path
    (a plain path line: the test venv's own .pth files, such as an editable install's
    finder, are not run, so `app` and `core` can only come from the wheel)."""
    target = tmp_path_factory.mktemp("venv") / "venv"
    run([sys.executable, "-m", "venv", "--without-pip", str(target)], cwd=target.parent)
    python = target / "bin" / "python"
    purelib = run([str(python), "-c", "import sysconfig; print(sysconfig.get_path('purelib'))"],
                  cwd=target).stdout.strip()
    (Path(purelib) / "alphascoop-test-deps.pth").write_text(sysconfig.get_path("purelib") + "\n")
    run([sys.executable, "-m", "pip", "--python", str(python), "install", "--no-deps",
         "--no-index", "-q", str(wheel)], cwd=target.parent)
    return target


def test_wheel_ships_every_module_and_the_assets(wheel: Path) -> None:
    """Every .py file of app/ and core/, the bundled files and the compiled library (with
    geogram's licence) are in the wheel; nothing else of the repository (tests, benchmarks,
    docs, the C++ sources) is."""
    names = set(zipfile.ZipFile(wheel).namelist())
    shipped = {name for name in names if not name.startswith("alphascoop-")}
    assert shipped == source_modules() | ASSETS | NATIVE
    assert any(name.endswith(f".dist-info/{NATIVE_LICENCE}") for name in names)


def test_installed_package_and_assets_come_from_the_venv(venv: Path) -> None:
    """Outside the repository the installed `app` and `core` are imported, and the bundled
    sample and icon are files inside the venv."""
    script = ("import app, core; from app.resources import SAMPLE_PATH, ICON_PATH; "
              "print(app.__file__, core.__file__, SAMPLE_PATH, ICON_PATH, "
              "SAMPLE_PATH.is_file(), ICON_PATH.is_file())")
    out = run([str(venv / "bin" / "python"), "-c", script], cwd=venv.parent).stdout.split()
    assert all(Path(path).is_relative_to(venv) for path in out[:4]), out
    assert out[4:] == ["True", "True"]


def test_installed_weighted_build_uses_the_compiled_library(venv: Path) -> None:
    """The installed package loads its own compiled library: a weighted build by geogram."""
    script = ("import numpy as np; from core import AlphaComplex; import core.backends.geogram "
              "as g; rng = np.random.default_rng(0); ac = AlphaComplex.from_points("
              "rng.random((300, 3)), weights=rng.random(300) * 1e-3); "
              "print(g.available(), ac.build_info.backend, g.__file__)")
    out = run([str(venv / "bin" / "python"), "-c", script], cwd=venv.parent).stdout.split()
    assert out[:2] == ["True", "geogram"] and Path(out[2]).is_relative_to(venv), out


def test_installed_command_renders_the_sample(venv: Path) -> None:
    """`alphascoop --optimal --screenshot out.png` (the installed script, run in a temporary
    folder) writes a PNG of the requested size showing a shape, not a blank frame."""
    work = venv.parent
    run([str(venv / "bin" / "alphascoop"), "--optimal", "--screenshot", "out.png",
         "--size", f"{SIZE[0]}x{SIZE[1]}"], cwd=work)
    image = np.asarray(Image.open(work / "out.png").convert("RGB"))
    assert image.shape == (SIZE[1], SIZE[0], 3)
    assert image_contrast(image) > MIN_CONTRAST
    background = image[0, -1]  # the top right corner: no legend, no axes there
    away = np.abs(image.astype(np.int16) - background).max(axis=2) > 30
    assert away.mean() > MIN_SHAPE_FRACTION


def cached_tables(folder: Path) -> list[Path]:
    """Finished table cache entries in folder (temporaries start with a dot)."""
    return [path for path in folder.glob("*.npz") if not path.name.startswith(".")]


@pytest.mark.gui
def test_installed_window_opens_on_the_sample(venv: Path, tmp_path: Path) -> None:
    """The installed `alphascoop` (no file, the session's display) opens the window and builds
    the bundled sample: its table lands in a private cache while the window is still up."""
    cache = tmp_path / "cache"
    env = outside_env(ALPHASCOOP_CACHE_DIR=str(cache), XDG_CONFIG_HOME=str(tmp_path / "config"))
    window = subprocess.Popen([str(venv / "bin" / "alphascoop"), "--size", "400x300"],
                              cwd=tmp_path, env=env, stdout=subprocess.PIPE,
                              stderr=subprocess.PIPE, text=True)
    try:
        deadline = time.monotonic() + STEP_TIMEOUT_S
        while not cached_tables(cache) and window.poll() is None and time.monotonic() < deadline:
            time.sleep(POLL_S)
        running = window.poll() is None
    finally:
        window.terminate()
        _, errors = window.communicate(timeout=STEP_TIMEOUT_S)
    assert running, f"the window exited early:\n{errors}"
    assert len(cached_tables(cache)) == 1, errors
    assert "Traceback" not in errors

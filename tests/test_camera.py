"""Which way is up (app.camera): by format, from a PCD VIEWPOINT, and the view presets."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from reference import data_dir, needs_data

from app.camera import PRESETS, Y_UP, Z_UP, frame_for, quaternion_matrix
from core.io import read_points

DATA = data_dir()


def write_pcd(path: Path, viewpoint: str) -> Path:
    """A small ascii PCD with the given VIEWPOINT line (7 numbers)."""
    points = np.random.default_rng(0).random((20, 3))
    header = (f"VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH 20\n"
              f"HEIGHT 1\nVIEWPOINT {viewpoint}\nPOINTS 20\nDATA ascii\n")
    path.write_text(header + "\n".join(" ".join(f"{v:.6f}" for v in p) for p in points) + "\n")
    return path


@pytest.mark.parametrize("preset", PRESETS)
@pytest.mark.parametrize("frame", [Z_UP, Y_UP])
def test_presets_look_across_the_up_axis(frame, preset) -> None:
    """Every preset's view up is perpendicular to its look direction; top looks down."""
    look, up = frame.direction(preset)
    assert np.linalg.norm(look) == pytest.approx(1.0) and abs(look @ up) < 1e-12
    if preset == "top":
        assert look @ np.asarray(frame.up) == pytest.approx(-1.0)
    elif preset == "iso":
        assert look @ np.asarray(frame.up) < -0.3 and up @ np.asarray(frame.up) > 0.5
    else:
        assert np.allclose(up, frame.up)


def test_quaternion_matrix_is_a_rotation() -> None:
    rotation = quaternion_matrix(np.cos(0.25 * np.pi), np.sin(0.25 * np.pi), 0.0, 0.0)
    assert np.allclose(rotation @ rotation.T, np.eye(3))
    assert np.allclose(rotation @ [0, 1, 0], [0, 0, 1])  # 90 degrees about x


def test_pcd_viewpoint_is_the_sensor_view(tmp_path) -> None:
    """PCL's camera frame looks along +z with y down; the VIEWPOINT rotates it."""
    identity = write_pcd(tmp_path / "a.pcd", "0 0 0 1 0 0 0")
    frame = frame_for(identity, read_points(identity).report)
    assert frame.start == "front"
    assert np.allclose(frame.up, [0, -1, 0]) and np.allclose(frame.front, [0, 0, 1])
    half = np.sqrt(0.5)
    turned = write_pcd(tmp_path / "b.pcd", f"1 2 3 {half} {half} 0 0")  # 90 degrees about x
    frame = frame_for(turned, read_points(turned).report)
    assert np.allclose(frame.up, [0, 0, -1]) and np.allclose(frame.front, [0, -1, 0])


def test_graphics_formats_are_y_up_and_others_z_up(tmp_path) -> None:
    points = np.random.default_rng(1).random((30, 3))
    ply = tmp_path / "p.ply"
    ply.write_text("ply\nformat ascii 1.0\nelement vertex 30\nproperty float x\nproperty float y\n"
                   "property float z\nend_header\n"
                   + "\n".join(" ".join(map(str, p)) for p in points) + "\n")
    assert frame_for(ply, read_points(ply).report) == Y_UP
    np.save(tmp_path / "p.npy", points)
    assert frame_for(tmp_path / "p.npy", read_points(tmp_path / "p.npy").report) == Z_UP


@needs_data
@pytest.mark.parametrize("name", ["autzen_trim.las", "plane_flat.laz"])
def test_lidar_is_z_up(name) -> None:
    path = DATA / name
    assert frame_for(path, read_points(path).report) == Z_UP

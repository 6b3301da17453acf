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


CORPUS = Path(__file__).resolve().parent / "data" / "corpus"
needs_data = pytest.mark.skipif(DATA is None, reason="shared real scans absent")


def opening_view(path: Path) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(look, view up, points) of the view a file opens with."""
    ps = read_points(path)
    frame = frame_for(path, ps.report, ps.points)
    look, up = frame.direction(frame.start)
    assert np.linalg.norm(look) == pytest.approx(1.0) and abs(look @ up) < 1e-9
    return look, up, ps.points


def spread(points: np.ndarray, direction: np.ndarray) -> float:
    """Extent of the points along a unit direction."""
    along = points @ direction
    return float(along.max() - along.min())


def test_a_plane_of_points_opens_face_on() -> None:
    """pcl_colored_cloud.pcd (points with normals on a tilted plane) is seen face-on: the
    points spread along the look direction less than 2 % of their spread across it (it
    opened edge-on, from the front preset of its VIEWPOINT); the sensor's up stays up."""
    look, up, points = opening_view(CORPUS / "pcd" / "pcl_colored_cloud.pcd")
    across = min(spread(points, up), spread(points, np.cross(look, up)))
    assert spread(points, look) < 0.02 * across
    assert up @ np.array([0.0, -1.0, 0.0]) > 0.3  # PCL's camera frame: y down


def test_a_y_up_e57_bunny_opens_upright_not_from_the_top() -> None:
    """libe57_bunnyInt32.e57 (no pose: the file does not say which way is up) opens along
    its thinnest axis with y up on screen (z up showed it from the top)."""
    look, up, points = opening_view(CORPUS / "e57" / "libe57_bunnyInt32.e57")
    assert up @ np.array([0.0, 1.0, 0.0]) > 0.8
    assert spread(points, look) < min(spread(points, up), spread(points, np.cross(look, up)))


def test_an_e57_pose_says_which_way_is_up() -> None:
    """pye57_translationWithoutRotation.e57 has a pose (identity rotation): z is up."""
    ps = read_points(CORPUS / "e57" / "pye57_translationWithoutRotation.e57")
    assert ps.report.view is not None and ps.report.view.up == (0.0, 0.0, 1.0)


@needs_data
def test_lidar_opens_from_above_with_north_up() -> None:
    """autzen_trim.las: looking down its thinnest axis (z, from the file), y (north) up."""
    look, up, _ = opening_view(DATA / "autzen_trim.las")
    assert look[2] < -0.99 and up[1] > 0.99


@needs_data
def test_a_ply_scan_opens_along_its_thinnest_axis_y_up() -> None:
    """bunny.ply: seen along its thinnest axis, from in front (+z), y up on screen."""
    look, up, points = opening_view(DATA / "bunny.ply")
    assert up[1] > 0.8 and look[2] < -0.8
    assert spread(points, look) < min(spread(points, up), spread(points, np.cross(look, up)))


@needs_data
def test_a_pcd_scan_keeps_the_sensor_up() -> None:
    """milk.pcd (VIEWPOINT identity: y down) opens with -y up, seen from the sensor's side."""
    look, up, _ = opening_view(DATA / "milk.pcd")
    assert up[1] < -0.8 and look[2] > 0.5


@pytest.mark.parametrize("name", ["ply/pcl_cube.ply", "gltf/trimesh_cube.glb"])
def test_a_cube_has_no_thinnest_axis_and_opens_iso(name) -> None:
    """A cube spreads alike along every axis: it opens with the iso preset (seen along an
    arbitrary axis it was a square)."""
    ps = read_points(CORPUS / name)
    assert frame_for(CORPUS / name, ps.report, ps.points).start == "iso"

"""The scene: the only package that imports VTK, pyvista or pyvistaqt (tests/test_app_layering.py).

It owns the plotter (a Qt widget in the window, off-screen for --screenshot) and everything
drawn in it: the layers' meshes and actors (layers), the annotations (overlay), the clipping
plane (clipping), colour-by's mapper state (painting) and picking with its highlight
(picking). Other modules hand it numpy arrays (data.SceneData, shapes) and styles.
"""

from app.scene.data import SceneData, as_xyz, exposed_of, pockets_of, scene_data
from app.scene.layers import KINDS_2D, KINDS_3D, ball_mesh
from app.scene.view import Scene

__all__ = ["KINDS_2D", "KINDS_3D", "Scene", "SceneData", "as_xyz", "ball_mesh", "exposed_of",
           "pockets_of", "scene_data"]

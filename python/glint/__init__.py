"""Glint from Python: scenes in, NumPy frames and error curves out (docs/python.md).

    import glint
    scene = glint.load_scene("scenes/cornell.json")
    frame = scene.render(spp=16, seed=1, aovs=["depth", "normal"])
    frame.rgba            # H x W x 4 float32, a view of the frame's pixels
    frame.stats["estimated_rmse"]
    frame.write("cornell.exr")   # the EXR `glint render` writes
"""
from ._glint import (Frame, Scene, SceneError, __version__, compare, default_scene, load_scene,
                     read_frame, validate)

__all__ = ["Frame", "Scene", "SceneError", "__version__", "compare", "default_scene",
           "load_scene", "read_frame", "validate"]

"""Shared by the Python module's tests: the module from the build (GLINT_BUILD, default build/),
the command beside it, and a small scene whose renders take milliseconds."""
import os
import pathlib
import sys

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
BUILD = pathlib.Path(os.environ.get("GLINT_BUILD", ROOT / "build"))
sys.path.insert(0, str(BUILD / "python"))

import glint  # noqa: E402  (after the build's module is on the path)

GLINT_BINARY = BUILD / "bin" / "glint"


def small_scene():
    """A Whitted still life of every kind of surface (matte, mirror, glass) and two lights,
    small enough that a frame of a few samples renders in milliseconds."""
    return {
        "render": {"width": 32, "height": 24, "spp": 4, "max_depth": 4, "seed": 1,
                   "background": [0.55, 0.7, 0.9], "ambient": [0.15, 0.15, 0.18]},
        "camera": {"type": "perspective", "eye": [0, 1.6, 6.5], "look_at": [0, 0.7, 0],
                   "up": [0, 1, 0], "vfov": 38},
        "materials": {
            "floor": {"type": "phong", "kd": {"checker": {"scale": 1.0, "a": [0.85, 0.85, 0.8],
                                                          "b": [0.12, 0.12, 0.14]}},
                      "ks": [0, 0, 0]},
            "clay": {"type": "phong", "kd": [0.75, 0.22, 0.12], "ks": [0.4, 0.4, 0.4],
                     "exponent": 60},
            "chrome": {"type": "mirror", "km": [0.85, 0.85, 0.88]},
            "glass": {"type": "dielectric", "ior": 1.5, "attenuation": [0.92, 0.98, 0.95]},
        },
        "lights": [
            {"type": "point", "position": [-4, 6, 5], "intensity": [0.8, 0.78, 0.72]},
            {"type": "quad", "corner": [-1, 5, -1], "edge1": [2, 0, 0], "edge2": [0, 0, 2],
             "intensity": [0.4, 0.4, 0.4], "samples": 2},
        ],
        "objects": [
            {"type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0], "material": "floor"},
            {"type": "sphere", "center": [-1.6, 0.8, -0.4], "radius": 0.8, "material": "clay"},
            {"type": "sphere", "center": [0.4, 1.0, -1.4], "radius": 1.0, "material": "chrome"},
            {"type": "sphere", "center": [1.5, 0.6, 0.9], "radius": 0.6, "material": "glass"},
        ],
    }


@pytest.fixture
def scene_dict():
    return small_scene()


@pytest.fixture
def binary():
    if not GLINT_BINARY.exists():
        pytest.fail(f"{GLINT_BINARY} is missing: build the command (cmake --build build)")
    return str(GLINT_BINARY)

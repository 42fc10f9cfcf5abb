"""Scene.render against `glint render`: the same pixels, AOVs, statistics and file."""
import json
import subprocess

import numpy as np
import pytest

import glint

# The settings both sides render with: stratified samples of an area light, so that a difference
# in the samples drawn would change the pixels; two threads, as tiles may finish in any order.
SETTINGS = dict(spp=4, seed=3, threads=2)
AOVS = ["depth", "normal", "albedo"]


def command_render(binary, scene_path, out, *extra):
    subprocess.run([binary, "render", str(scene_path), "-o", str(out), "--spp", "4", "--seed", "3",
                    "--threads", "2", "--quiet", *extra], check=True)


@pytest.fixture
def rendered(tmp_path, scene_dict, binary):
    """The dict rendered from Python, and the same scene as a JSON file by the command."""
    scene_path = tmp_path / "scene.json"
    scene_path.write_text(json.dumps(scene_dict, indent=2))
    command_render(binary, scene_path, tmp_path / "command.exr", "--aov", ",".join(AOVS),
                   "--stats-json", str(tmp_path / "stats.json"))
    frame = glint.Scene.from_dict(scene_dict).render(aovs=AOVS, **SETTINGS)
    return frame, glint.read_frame(tmp_path / "command.exr"), tmp_path


def test_dict_scene_renders_the_commands_pixels_bit_for_bit(rendered):
    frame, command, _ = rendered
    # Both are float32 rounded from the same doubles: any difference in a sample shows.
    assert frame.rgba.dtype == np.float32 and frame.rgba.shape == (24, 32, 4)
    assert np.array_equal(frame.rgba, command.rgba)
    # Not a blank frame that would equal any other: the scene's lights reach it.
    assert frame.rgba[..., :3].max() > 0.1 and frame.rgba[..., 3].min() == 1.0


def test_aov_arrays_equal_the_exr_layers(rendered):
    frame, command, _ = rendered
    assert set(frame.aovs) == set(AOVS)
    assert frame.aovs["depth"].shape == (24, 32, 1)
    assert np.array_equal(frame.aovs["depth"][..., 0], command.channel("Z"))
    for k, axis in enumerate("XYZ"):
        assert np.array_equal(frame.aovs["normal"][..., k], command.channel("N." + axis))
    for k, c in enumerate("RGB"):
        assert np.array_equal(frame.aovs["albedo"][..., k], command.channel("Albedo." + c))
    # The frame read back names its AOVs as the render does, and holds the same arrays.
    assert set(command.aovs) == set(AOVS)
    for name in AOVS:
        assert np.array_equal(command.aovs[name], frame.aovs[name])
    # Where every sample hit a surface (a miss's depth is 1e10), each pixel's normal is a mean of
    # unit normals: at most 1, and 1 inside a surface (the floor's is exactly (0, 1, 0)).
    hit = frame.aovs["depth"][..., 0] < 1e3
    assert hit.mean() > 0.5
    lengths = np.linalg.norm(frame.aovs["normal"][hit], axis=-1)
    assert lengths.max() <= 1 + 1e-5 and np.median(lengths) > 0.99


def test_arrays_are_views_of_one_buffer(rendered):
    frame, _, _ = rendered
    # No copy: each array's base is the frame, and views of one buffer share its memory.
    assert frame.rgba.base is frame and frame.aovs["normal"].base is frame
    assert not frame.rgba.flags.writeable
    # One interleaved buffer: R, G, B, A, then the AOVs' channels in order (depth's Z first).
    start = frame.rgba.__array_interface__["data"][0]
    assert frame.aovs["depth"].__array_interface__["data"][0] == start + 4 * 4
    assert frame.aovs["normal"].__array_interface__["data"][0] == start + 5 * 4
    assert frame.rgba.strides == (32 * 11 * 4, 11 * 4, 4)


def test_stats_are_the_commands_stats_json(rendered):
    frame, _, tmp_path = rendered
    command = json.loads((tmp_path / "stats.json").read_text())
    assert set(frame.stats) == set(command)
    for key in ("seconds", "estimated_rmse", "estimated_relmse"):
        assert isinstance(frame.stats[key], float), key
    for key in ("rays_total", "nonfinite_samples", "clamped_values", "peak_rss_bytes"):
        assert isinstance(frame.stats[key], int), key
    assert set(frame.stats["rays"]) == {"camera", "shadow", "reflection", "refraction"}
    assert isinstance(frame.stats["features_used"], list)
    assert isinstance(frame.stats["features_left_out"], list)
    # The same samples give the same counts; the pass list is the same plan's.
    assert frame.stats["rays"] == command["rays"]
    assert frame.stats["rays_total"] == command["rays_total"]
    assert [p["spp"] for p in frame.stats["passes"]] == [p["spp"] for p in command["passes"]]
    assert frame.stats["estimated_rmse"] == command["estimated_rmse"]
    assert frame.stats["sampler"] == command["sampler"] == "stratified"


def test_write_is_the_exr_the_command_writes(rendered):
    _, command, tmp_path = rendered
    # The scene file itself: its bytes are part of the settings hash the record carries.
    frame = glint.load_scene(tmp_path / "scene.json").render(aovs=AOVS, **SETTINGS)
    frame.write(tmp_path / "python.exr")
    written = glint.read_frame(tmp_path / "python.exr")
    assert written.channels == command.channels
    assert np.array_equal(written.rgba, command.rgba)
    assert np.array_equal(written.channel("N.Y"), command.channel("N.Y"))
    # The record: the settings that make the pixels (its hash), the plan and the result.
    for key in ("glint:settings_hash", "glint:spp", "glint:seed", "glint:sampler",
                "glint:passes", "glint:min_pixel_spp", "glint:accel", "glint:integrator",
                "pixelAspectRatio"):
        if key == "glint:passes":
            assert [p["spp"] for p in written.record[key]] == \
                [p["spp"] for p in command.record[key]]
        else:
            assert written.record[key] == command.record[key], key
    assert written.record["glint:seed"] == 3 and written.record["glint:spp"] == 4
    assert written.record["pixelAspectRatio"] == 1.0  # the scene's vfov: square pixels


def test_multipart_frame_reads_as_the_single_part_one(rendered, binary):
    # --multipart puts each AOV in a part of its own: read_frame once returned part 0 alone, the
    # AOVs silently missing. Every part is read, under the single-part frame's channel names.
    _, command, tmp_path = rendered
    command_render(binary, tmp_path / "scene.json", tmp_path / "multipart.exr", "--aov",
                   ",".join(AOVS), "--multipart")
    multipart = glint.read_frame(tmp_path / "multipart.exr")
    assert sorted(multipart.channels) == sorted(command.channels)
    assert set(multipart.aovs) == set(command.aovs) == {"depth", "normal", "albedo"}
    for name in command.channels:
        assert np.array_equal(multipart.channel(name), command.channel(name)), name


def test_read_frame_names_only_glints_own_planes_as_aovs(tmp_path):
    # A layer is named as a render names its AOV only where its channels are exactly those of
    # the AOV's plane: another tool's two-channel N stays N, and its own layers keep their names.
    path = tmp_path / "other.exr"
    subprocess.run(["oiiotool", "--pattern", "constant:color=0.5,0.25,1,2,3,4,5", "4x2", "7",
                    "--chnames", "R,G,B,A,N.X,N.Y,Z", "-d", "float", "-o", str(path)], check=True)
    frame = glint.read_frame(path)
    assert set(frame.aovs) == {"N", "depth"}
    assert frame.aovs["N"].shape == (2, 4, 2) and np.all(frame.aovs["depth"] == 5)
    # A layer the file itself names "depth" keeps the name; its Z then keeps its own.
    subprocess.run(["oiiotool", "--pattern", "constant:color=0.5,0.25,1,2,3,4", "4x2", "6",
                    "--chnames", "R,G,B,A,depth.V,Z", "-d", "float", "-o", str(path)], check=True)
    frame = glint.read_frame(path)
    assert set(frame.aovs) == {"depth", "Z"}
    assert np.all(frame.aovs["depth"] == 3) and np.all(frame.aovs["Z"] == 4)


def test_crop_and_sampler_as_the_command(tmp_path, scene_dict, binary):
    scene_path = tmp_path / "scene.json"
    scene_path.write_text(json.dumps(scene_dict))
    command_render(binary, scene_path, tmp_path / "crop.exr", "--crop", "5", "21", "3", "17",
                   "--sampler", "sobol")
    frame = glint.Scene.from_dict(scene_dict).render(crop=(5, 21, 3, 17), sampler="sobol",
                                                     **SETTINGS)
    command = glint.read_frame(tmp_path / "crop.exr")
    assert frame.rgba.shape == (14, 16, 4) and frame.origin == (5, 3)
    assert np.array_equal(frame.rgba, command.rgba)


def test_load_scene_renders_as_the_command(tmp_path, binary):
    scene = glint.load_scene(str(glint_scenes() / "soft_shadows.json"))
    command_render(binary, glint_scenes() / "soft_shadows.json", tmp_path / "s.exr",
                   "--width", "24", "--height", "16")
    frame = scene.render(width=24, height=16, **SETTINGS)
    assert np.array_equal(frame.rgba, glint.read_frame(tmp_path / "s.exr").rgba)


def glint_scenes():
    from conftest import ROOT
    return ROOT / "scenes"

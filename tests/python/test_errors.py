"""Mistakes in scenes and arguments: clean Python exceptions, never a crash."""
import json
import math
import subprocess

import pytest

import glint


def test_scene_error_names_file_line_and_path(tmp_path):
    path = tmp_path / "bad.json"
    lines = ['{', '  "camera": {"eye": [0, 1, 5], "look_at": [0, 0, 0]},',
             '  "materials": {"m": {"type": "phong", "kd": [0.5, 0.5, 0.5]}},',
             '  "objects": [',
             '    {"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "m"},',
             '    {"type": "sphere", "center": [0, 0, 2], "radius": 1, "material": "m",',
             '     "colour": [1, 0, 0]}',
             '  ]', '}']
    path.write_text("\n".join(lines))
    with pytest.raises(glint.SceneError) as e:
        glint.load_scene(str(path))
    assert isinstance(e.value, ValueError)
    assert e.value.file == str(path)
    assert e.value.line == 7  # the line of the unknown key
    assert e.value.path == "objects[1].colour"
    assert str(e.value).startswith(f"{path}:7: objects[1].colour")


def test_dict_scene_error_names_the_path(scene_dict):
    scene_dict["objects"][2]["radius"] = -1
    with pytest.raises(glint.SceneError) as e:
        glint.Scene.from_dict(scene_dict)
    assert e.value.file == "<dict>" and e.value.line > 0
    assert e.value.path == "objects[2].radius"


def test_numpy_values_in_a_dict_scene_are_their_lists(scene_dict):
    # A notebook's eye or colour as NumPy values renders as the same scene given as lists.
    import numpy as np
    with_arrays = {**scene_dict, "camera": {**scene_dict["camera"],
                                            "eye": np.array(scene_dict["camera"]["eye"])}}
    a = glint.Scene.from_dict(scene_dict).render(spp=2, seed=3)
    b = glint.Scene.from_dict(with_arrays).render(spp=2, seed=3)
    np.testing.assert_array_equal(a.rgba, b.rgba)


def test_non_json_values_are_scene_errors(scene_dict):
    scene_dict["objects"][1]["radius"] = math.nan
    with pytest.raises(glint.SceneError, match="objects\\[1\\].radius: must be a finite number"):
        glint.Scene.from_dict(scene_dict)
    scene_dict["objects"][1]["radius"] = object()
    with pytest.raises(glint.SceneError, match="objects\\[1\\].radius"):
        glint.Scene.from_dict(scene_dict)
    loop = {}
    loop["render"] = loop
    with pytest.raises(glint.SceneError, match="nested deeper"):
        glint.Scene.from_dict(loop)
    with pytest.raises(TypeError):
        glint.Scene.from_dict([1, 2])
    with pytest.raises(glint.SceneError):
        glint.Scene.from_dict({1: 2})


@pytest.mark.parametrize("kwargs, message", [
    (dict(spp=-1), "spp must be from 1"),
    (dict(spp=0), "spp must be from 1"),
    (dict(spp=1 << 40), "spp must be from 1"),
    (dict(width=1 << 20), "width must be from 1"),
    (dict(threads=0), "threads must be from 1"),
    (dict(seed=-5), "seed must be from 0 to 2\\^64 - 1"),
    (dict(seed=1 << 64), "seed must be from 0 to 2\\^64 - 1"),
    (dict(crop=(0, 10)), "crop is"),
    (dict(crop=(10, 5, 0, 4)), "must be non-empty and inside"),
    (dict(crop=(0, 33, 0, 4)), "must be non-empty and inside"),
    (dict(aovs=["depth", "shadows"]), "shadows"),
    (dict(sampler="halton"), "sampler must be"),
    (dict(target_rmse=math.nan), "target_rmse must be a finite number above 0"),
    (dict(time_limit=-1.0), "time_limit must be"),
    (dict(accel="octopus"), "accel"),
])
def test_bad_render_arguments_raise_value_errors(scene_dict, kwargs, message):
    scene = glint.Scene.from_dict(scene_dict)
    with pytest.raises(ValueError, match=message):
        scene.render(**kwargs)


def test_bad_argument_types_raise_type_errors(scene_dict):
    scene = glint.Scene.from_dict(scene_dict)
    with pytest.raises(TypeError):
        scene.render(spp="many")
    with pytest.raises(TypeError):
        scene.render(progress=3)
    with pytest.raises(TypeError):
        scene.render(16)  # keywords only
    with pytest.raises(TypeError, match="seed must be an int"):
        scene.render(seed=1.5)


def test_missing_files_and_bad_outputs(tmp_path, scene_dict):
    with pytest.raises(ValueError):
        glint.load_scene(str(tmp_path / "none.json"))
    with pytest.raises(ValueError):
        glint.read_frame(tmp_path / "none.exr")
    frame = glint.Scene.from_dict(scene_dict).render(spp=1)
    with pytest.raises(ValueError):
        frame.write(tmp_path / "frame.bmp")
    with pytest.raises(KeyError):
        frame.channel("nope")


def test_an_output_name_cut_at_a_nul_replaces_nothing(tmp_path, scene_dict):
    # The C calls under Frame.write read "notes.txt\0.exr" as notes.txt: the frame replaced an
    # unrelated file, past the check that the extension names the format.
    notes = tmp_path / "notes.txt"
    notes.write_text("precious")
    frame = glint.Scene.from_dict(scene_dict).render(spp=1)
    for name in ("notes.txt\x00.exr", "n2\x00.png"):
        with pytest.raises(ValueError, match="control character"):
            frame.write(str(tmp_path / name))
    assert notes.read_text() == "precious"
    assert not (tmp_path / "n2").exists()


def test_paths_are_the_file_systems_bytes(tmp_path, scene_dict):
    # bytes were read as str(b"x.exr"), and a name that is not UTF-8 could not be given at all.
    frame = glint.Scene.from_dict(scene_dict).render(spp=1)
    for name in (b"bytes.exr", "lat\udce9.exr"):
        path = tmp_path / name.decode("utf-8", "surrogateescape") if isinstance(name, bytes) \
            else tmp_path / name
        given = bytes(tmp_path) + b"/" + name if isinstance(name, bytes) else str(path)
        frame.write(given)
        assert path.exists(), name
        assert glint.read_frame(given).rgba.shape == frame.rgba.shape
        assert glint.compare(given, frame)["rmse"] == 0


def test_validate_takes_a_scene_and_something_to_cast(scene_dict):
    # A path gave pybind11's "Unable to cast Python instance"; rays=0 with spp=0 checked no ray
    # and reported an agreement of 1.
    scene = glint.Scene.from_dict(scene_dict)
    with pytest.raises(TypeError, match="scene must be a glint.Scene"):
        glint.validate("scene.json", rays=10)
    with pytest.raises(ValueError, match="casts no ray"):
        glint.validate(scene, rays=0, spp=0)


def test_a_frame_read_alone_may_be_written_again(tmp_path, scene_dict):
    # read_frame and compare noted the file as an input of "this run", which in an interpreter
    # is the session: writing it again was refused for good.
    scene = glint.Scene.from_dict(scene_dict)
    path = tmp_path / "again.exr"
    scene.render(spp=1).write(path)
    glint.read_frame(path)
    glint.compare(path, path)
    scene.render(spp=2).write(path)
    assert glint.read_frame(path).record["glint:spp"] == 2


def test_every_seed_the_command_line_takes(scene_dict):
    # Seeds past 2^63, which --seed takes and frames record, were an opaque TypeError.
    frame = glint.Scene.from_dict(scene_dict).render(spp=1, seed=(1 << 64) - 1)
    assert frame.record["glint:seed"] == (1 << 64) - 1


def test_a_display_image_refuses_what_only_an_exr_carries(tmp_path, scene_dict):
    # half=True and a frame's AOVs were dropped from a .png without a word; the command refuses
    # the same (-o x.png --half).
    scene = glint.Scene.from_dict(scene_dict)
    with pytest.raises(ValueError, match="cannot carry half=True"):
        scene.render(spp=1).write(tmp_path / "half.png", half=True)
    with pytest.raises(ValueError, match="cannot carry the frame's AOVs"):
        scene.render(spp=1, aovs=["depth"]).write(tmp_path / "aovs.png")
    assert not (tmp_path / "half.png").exists() and not (tmp_path / "aovs.png").exists()
    scene.render(spp=1).write(tmp_path / "plain.png")
    assert (tmp_path / "plain.png").exists()


def test_a_resumable_frames_state_is_not_an_aov(tmp_path, scene_dict, binary):
    # A --resumable frame listed its 23 glint_resume channels among .aovs; they are Glint's bits.
    scene = tmp_path / "scene.json"
    scene.write_text(json.dumps(scene_dict))
    subprocess.run([binary, "render", str(scene), "--spp", "2", "--resumable", "--quiet", "-o",
                    str(tmp_path / "r.exr")], check=True)
    frame = glint.read_frame(tmp_path / "r.exr")
    assert frame.aovs == {}
    assert frame.channel("glint_resume.00").shape == frame.rgba.shape[:2]
    with pytest.raises(TypeError, match="not None"):
        glint.compare(None, frame)

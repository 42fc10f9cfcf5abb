"""Driving a render: progress and cancelling, Ctrl-C, and many renders in one process."""
import os
import signal
import subprocess
import sys
import textwrap

import numpy as np
import pytest

import glint
from conftest import BUILD


def test_progress_is_called_after_each_pass(scene_dict):
    seen = []
    frame = glint.Scene.from_dict(scene_dict).render(spp=16, seed=1, progress=seen.append)
    # One call per pass of the plan, the samples per pixel growing to the frame's 16.
    assert len(seen) == len(frame.stats["passes"]) >= 2
    assert [p["spp"] for p in seen] == [p["spp"] for p in frame.stats["passes"]]
    assert seen[-1]["spp"] == 16 and not frame.partial
    assert all(a["seconds"] <= b["seconds"] for a, b in zip(seen, seen[1:]))
    assert isinstance(seen[0]["estimated_rmse"], float)


def test_progress_returning_false_cancels(scene_dict):
    calls = []

    def stop_after_first(info):
        calls.append(info)
        return False

    scene = glint.Scene.from_dict(scene_dict)
    frame = scene.render(spp=64, seed=1, threads=1, progress=stop_after_first)
    # Cancelled after the first pass (the next pass waits for the callback's answer): one call,
    # and the frame is that pass's, marked partial, far short of the 64 samples asked for.
    assert len(calls) == 1 and frame.partial
    assert [p["spp"] for p in frame.stats["passes"]] == [calls[0]["spp"]] and calls[0]["spp"] < 64
    assert frame.record["glint:partial"] is True
    # Every pixel holds the first pass's samples, and no pixel more.
    assert frame.stats["pixel_spp"]["min"] == frame.stats["pixel_spp"]["max"] == calls[0]["spp"]


def test_a_callback_answer_without_a_truth_value_is_raised(scene_dict):
    # NumPy refuses bool() of a two-element array: that error, not a SystemError, comes back.
    try:
        glint.Scene.from_dict(scene_dict).render(spp=16, threads=1,
                                                 progress=lambda info: np.array([1, 0]))
    except ValueError as e:
        assert "truth value" in str(e) and e.frame.partial
    else:
        raise AssertionError("the answer's error was lost")


def test_progress_exception_stops_and_propagates(scene_dict):
    def fail(info):
        raise RuntimeError("stop here")

    try:
        glint.Scene.from_dict(scene_dict).render(spp=64, threads=1, progress=fail)
    except RuntimeError as e:
        assert str(e) == "stop here"
        assert e.frame.partial  # the finished passes travel with it
    else:
        raise AssertionError("the callback's exception was swallowed")


def test_sigint_raises_keyboard_interrupt_with_the_finished_passes():
    # A long render in a child process, interrupted after its first pass: KeyboardInterrupt,
    # with the finished passes on the exception, within the command's latency (the chunk of
    # samples in flight), far inside the bound given here.
    child = textwrap.dedent(f"""
        import signal, sys, time
        # Python keeps SIGINT ignored when it starts ignored (a background job of a script, as CI
        # may run this suite); a terminal's user has Python's own handler, which this installs.
        signal.signal(signal.SIGINT, signal.default_int_handler)
        sys.path.insert(0, {str(BUILD / 'python')!r})
        import glint
        scene = glint.default_scene()
        def started(info):
            print("pass", info["spp"], flush=True)
        try:
            scene.render(width=320, height=200, spp=1 << 16, threads=1, progress=started)
        except KeyboardInterrupt as e:
            f = e.frame
            print("interrupted", f.partial, len(f.stats["passes"]), f.rgba.shape, flush=True)
        else:
            print("finished", flush=True)
    """)
    p = subprocess.Popen([sys.executable, "-c", child], stdout=subprocess.PIPE, text=True)
    try:
        first = p.stdout.readline()
        assert first.startswith("pass"), first
        p.send_signal(signal.SIGINT)
        out, _ = p.communicate(timeout=60)
    finally:
        if p.poll() is None:
            p.kill()
    assert p.returncode == 0
    assert "interrupted True" in out and "(200, 320, 4)" in out, out


def rss_bytes():
    with open("/proc/self/statm") as f:
        return int(f.read().split()[1]) * os.sysconf("SC_PAGE_SIZE")


def test_no_leak_across_200_renders(scene_dict):
    scene = glint.Scene.from_dict(scene_dict)
    settings = dict(width=64, height=64, spp=1, threads=1, aovs=["depth", "normal", "albedo"])
    for _ in range(20):  # the allocator's and the thread pool's first growth
        scene.render(**settings)
    before = rss_bytes()
    for i in range(180):
        frame = scene.render(seed=i, **settings)
        assert frame.rgba.shape == (64, 64, 4)
    grown = rss_bytes() - before
    # A frame holds ~0.9 MB (the film, its AOVs, the pixels' estimates): 180 kept would add
    # ~160 MB, measured; dropped, they add ~1 MB. The bound leaves room for the
    # allocator's slack.
    assert grown < 24 << 20, grown


def test_validate_compare_read_frame_version(tmp_path, scene_dict):
    scene = glint.Scene.from_dict(scene_dict)
    v = glint.validate(scene, rays=2000)
    # Every backend agrees with Embree on this scene of spheres and a plane.
    assert v["hit_agreement"] == 1.0 and v["occlusion_agreement"] == 1.0
    assert v["rays"] > 2000 and "max_rel_dt" in v
    a = scene.render(spp=1, seed=1)
    b = scene.render(spp=64, seed=1)
    same = glint.compare(a, a)
    assert same["rmse"] == 0 and same["psnr"] is None  # +inf written as None, as --json does
    assert same["nonfinite_pixels"] == 0  # told from a None that non-finite pixels make
    broken = a.rgba.copy()
    broken[0, 0, 0] = np.nan
    with pytest.warns(UserWarning, match="1 of 768 pixels hold a NaN or infinite R, G or B"):
        assert glint.compare(broken, a)["nonfinite_pixels"] == 1
    with pytest.raises(ValueError, match="images differ in size: a \\(an array\\) is "
                       "24x32, b \\(a Frame\\) 32x24"):
        glint.compare(np.zeros((32, 24, 3), np.float32), a)
    err = glint.compare(a.rgba, b.rgba)
    assert err["rmse"] > 0 and err["pixels"] == 32 * 24
    a.write(tmp_path / "a.exr")
    b.write(tmp_path / "b.exr")
    assert glint.compare(str(tmp_path / "a.exr"), tmp_path / "b.exr") == err
    # RMSE by hand over RGB, the definition compare uses.
    d = (a.rgba[..., :3].astype(np.float64) - b.rgba[..., :3])
    assert abs(err["rmse"] - np.sqrt((d * d).mean())) < 1e-6
    assert glint.__version__.count(".") == 2

#!/usr/bin/env python3
"""The most any per-pixel allocation of samples can save on a scene (docs/validation.md,
"Adaptive sampling against uniform sampling", what is behind on depth_of_field).

At a level of N samples a pixel, each pixel's error variance v (mean over R, G, B) is measured
from --runs independent uniform renders of N spp, and its cost c (rays a sample) from one
resumable render (the rays its resume state counts). Given those exact values, Neyman's
allocation with a first pass of m samples everywhere, n = max(m, lambda * sqrt(v N / c)) with
lambda set so that the frame's mean error variance equals uniform's, traces the fewest rays an
allocation can for uniform's error (assuming each pixel's error falls as 1/n near N). The table
gives uniform's samples and rays over the oracle's: adaptive sampling, which must estimate v
from the pixel's own samples and takes its samples in doubling passes, can only do worse.
The sample noise of v (runs - 1 degrees of freedom) flatters the oracle a little.

    tools/adaptive-oracle.py --scene depth_of_field --levels 32 64 128
"""
import argparse
import math
import struct
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def render(args, out, spp, seed, extra=()):
    subprocess.run([args.glint, "render", str(args.scene_path), "-o", str(out), "--quiet",
                    "--width", str(args.size[0]), "--height", str(args.size[1]), "--spp",
                    str(spp), "--seed", str(seed), *extra], check=True)


def channels(args, image, names, scale=None):
    """The named channels of an EXR as floats, pixel-interleaved (through oiiotool's FITS,
    which Python reads without libraries; FITS runs bottom-up, the same for every image)."""
    fits = image.with_suffix(".fits")
    cmd = ["oiiotool", str(image), "--ch", ",".join(names)]
    if scale:  # UINT channels read as value / scale
        cmd += ["-d", "double", "--mulc", repr(scale)]
    subprocess.run(cmd + ["-d", "float", "-o", str(fits)], check=True)
    data = fits.read_bytes()
    count = args.size[0] * args.size[1] * len(names)
    return struct.unpack(f">{count}f", data[len(data) - 4 * count:])  # the data ends the file


def oracle(v, c, level, first, weigh_cost):
    """Uniform's samples and rays over the oracle allocation's, at uniform's error."""
    pixels = len(v)
    per_sample = [vi * level for vi in v]
    weight = c if weigh_cost else [1.0] * pixels
    goal = sum(v) / pixels

    def counts(lam):
        return [max(first, lam * math.sqrt(s / w)) for s, w in zip(per_sample, weight)]

    lo, hi = 1e-12, 1e12
    for _ in range(200):  # bisect lambda in log space: the frame's error falls as it grows
        mid = math.sqrt(lo * hi)
        if sum(s / n for s, n in zip(per_sample, counts(mid))) / pixels > goal:
            lo = mid
        else:
            hi = mid
    n = counts(hi)
    return (level * pixels / sum(n),
            sum(ci * level for ci in c) / sum(ci * ni for ci, ni in zip(c, n)))


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--glint", default=str(ROOT / "build" / "bin" / "glint"))
    p.add_argument("--scene", default="depth_of_field")
    p.add_argument("--size", type=int, nargs=2, default=[240, 150])
    p.add_argument("--levels", type=int, nargs="+", default=[32, 64, 128])
    p.add_argument("--first-passes", type=int, nargs="+", default=[1, 4, 8, 16])
    p.add_argument("--runs", type=int, default=16)
    args = p.parse_args()
    args.scene_path = ROOT / "scenes" / f"{args.scene}.json"
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        rays = tmp / "rays.exr"
        render(args, rays, 64, 7, ["--resumable"])
        # Per half: the sample count is channel 8 of 11, the rays' low word channel 10.
        state = channels(args, rays, ["glint_resume.08", "glint_resume.10", "glint_resume.19",
                                      "glint_resume.21"], 4294967295.0)
        c = [max(1.0, (round(state[i + 1]) + round(state[i + 3])) /
                 max(1, round(state[i]) + round(state[i + 2])))
             for i in range(0, len(state), 4)]
        print(f"{args.scene} at {args.size[0]} x {args.size[1]}: {sum(c) / len(c):.2f} rays a "
              f"sample; uniform's samples and rays over the oracle's (> 1: fewer needed)\n")
        print("| level | first pass | n ~ sigma: samples | rays | n ~ sigma/sqrt(c): samples | rays |")
        print("|---:|---:|---:|---:|---:|---:|")
        for level in args.levels:
            images = []
            for k in range(args.runs):
                image = tmp / f"u{level}-{k}.exr"
                render(args, image, level, 101 + k)
                images.append(channels(args, image, ["R", "G", "B"]))
            v = []
            for i in range(len(c)):
                total = 0.0
                for ch in range(3):
                    xs = [im[3 * i + ch] for im in images]
                    mean = sum(xs) / len(xs)
                    total += sum((x - mean) ** 2 for x in xs) / (len(xs) - 1) / 3
                v.append(total)
            for first in args.first_passes:
                if first > level:
                    continue
                a, b = oracle(v, c, level, first, False), oracle(v, c, level, first, True)
                print(f"| {level} | {first} | {a[0]:.2f} | {a[1]:.2f} | {b[0]:.2f} | {b[1]:.2f} |",
                      flush=True)


if __name__ == "__main__":
    sys.exit(main())

#!/usr/bin/env python3
"""Glint against Embree's `pathtracer` on its Cornell box, side by side (docs/peers.md).

Whole processes, 2 threads each: `glint render scenes/peers/cornell_box.json` and
`pathtracer --max-path-length 1 --spp 16` (the same work: one camera and one shadow ray per
sample). After one warm-up of each, every round runs Glint, the pathtracer, the pathtracer,
Glint, so that load from other processes hits both alike. Prints each program's median wall
and CPU seconds (user + system of the process, from getrusage) and Glint's over the
pathtracer's. With --baseline, a second Glint binary (a build side by side) joins each round.

Needs embree-tools (Debian) for the pathtracer and its model.
"""

import argparse
import pathlib
import resource
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

ROOT = pathlib.Path(__file__).resolve().parents[2]
MODEL = "/usr/share/doc/embree3/models/cornell_box.ecs"


def timed(command):
    """Wall and CPU seconds of one run of `command`."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    subprocess.run(command, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, check=True)
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return wall, (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--glint", default=str(ROOT / "build/bin/glint"))
    parser.add_argument("--baseline", help="another glint binary, timed in the same rounds")
    parser.add_argument("--rounds", type=int, default=5)
    args = parser.parse_args()
    if args.rounds < 1:
        sys.exit("time_cornell.py: --rounds must be at least 1")
    if not shutil.which("pathtracer") or not pathlib.Path(MODEL).exists():
        sys.exit("time_cornell.py: needs Embree's pathtracer and its model: "
                 "apt-get install embree-tools")
    out = pathlib.Path(tempfile.mkdtemp(prefix="glint-cornell-"))
    scene = str(ROOT / "scenes/peers/cornell_box.json")
    programs = {"glint": [args.glint, "render", scene, "--threads", "2", "--quiet",
                          "-o", str(out / "glint.exr")]}
    if args.baseline:
        programs["baseline"] = [args.baseline, "render", scene, "--threads", "2", "--quiet",
                                "-o", str(out / "baseline.exr")]
    programs["pathtracer"] = ["pathtracer", "-c", MODEL, "-o", str(out / "pathtracer.pfm"),
                              "--spp", "16", "--threads", "2", "--max-path-length", "1"]
    names = list(programs)
    try:
        for name in names:
            timed(programs[name])
        runs = {name: [] for name in names}
        for _ in range(args.rounds):
            for name in names + names[::-1]:
                runs[name].append(timed(programs[name]))
    finally:
        shutil.rmtree(out)
    median = {name: (statistics.median(w for w, _ in runs[name]),
                     statistics.median(c for _, c in runs[name])) for name in names}
    print(f"medians of {2 * args.rounds} runs each")
    print("| program | wall s | CPU s |\n|---|---:|---:|")
    for name in names:
        print(f"| {name} | {median[name][0]:.3f} | {median[name][1]:.3f} |")
    reference = median["pathtracer"]
    for name in names[:-1]:
        print(f"{name} over pathtracer: wall {median[name][0] / reference[0]:.3f}, "
              f"CPU {median[name][1] / reference[1]:.3f}")
    if args.baseline:
        print(f"glint over baseline: wall {median['glint'][0] / median['baseline'][0]:.3f}, "
              f"CPU {median['glint'][1] / median['baseline'][1]:.3f}")


if __name__ == "__main__":
    main()

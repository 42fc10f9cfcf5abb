#!/usr/bin/env python3
"""Ray classification's n_min and w_min against time per ray (docs/acceleration.md).

For each scene and each (n_min, w_min) pair, runs
  glint bench SCENE --structures --accel bvh,rayclass --random-rays R
        --rayclass-n-min N --rayclass-w-min W --json OUT
and prints one markdown row: one thread's time per camera ray and per random ray in the first
pass through a fresh structure (the cells made while tracing included, as in a render), each also
as a ratio to the reference BVH's best pass in the same process (the ratio survives a shared
machine's load), the objects tested per ray, and the bytes made.

  tools/rayclass_sweep.py --scenes scenes/objects.json,scenes/wuson.json \\
      --n-min 2,8 --w-min 0.03125,0.0078125,0.001953125
"""

import argparse
import itertools
import json
import subprocess
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("--glint", default=str(ROOT / "build/bin/glint"))
    ap.add_argument("--scenes", required=True, help="comma-separated scene files")
    ap.add_argument("--n-min", default="2,8", help="comma-separated n_min values")
    ap.add_argument("--w-min", default="0.03125,0.0078125,0.001953125",
                    help="comma-separated w_min values")
    ap.add_argument("--random-rays", type=int, default=5000)
    args = ap.parse_args()
    print("| scene | n_min | w_min | camera ns (first pass) | × bvh | camera tests | "
          "random ns (first pass) | × bvh | random tests | MiB |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp) / "bench.json"
        for scene in args.scenes.split(","):
            for n, w in itertools.product(args.n_min.split(","), args.w_min.split(",")):
                subprocess.run([args.glint, "bench", scene, "--structures", "--accel", "bvh,rayclass",
                                "--random-rays", str(args.random_rays), "--rayclass-n-min", n,
                                "--rayclass-w-min", w, "--json", str(out)],
                               check=True, stdout=subprocess.DEVNULL)
                s = json.loads(out.read_text())["structures"]
                b, r = s["bvh"], s["rayclass"]
                cam, rnd = r["camera_first_pass_ns_per_ray"], r["random_first_pass_ns_per_ray"]
                print(f"| {Path(scene).name} | {n} | {float(w):g} | {cam:.0f} | "
                      f"{cam / b['camera_ns_per_ray']:.1f} | {r['camera_tests_per_ray']:.1f} | "
                      f"{rnd:.0f} | {rnd / b['random_ns_per_ray']:.1f} | "
                      f"{r['random_tests_per_ray']:.1f} | {r['bytes'] / 2**20:.1f} |", flush=True)


if __name__ == "__main__":
    main()

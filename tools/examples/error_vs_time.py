#!/usr/bin/env python3
"""Error against render time on a bundled scene: three samplers at doubling sample counts, and
adaptive sampling at halving error targets, each against a high-sample reference; one PNG.

    PYTHONPATH=build/python /usr/bin/python3 tools/examples/error_vs_time.py -o error_vs_time.png

docs/python.md explains it line by line.
"""
import argparse
import pathlib
import sys

import matplotlib

matplotlib.use("Agg")  # a file, no display needed
import matplotlib.pyplot as plt  # noqa: E402

import glint  # noqa: E402

ROOT = pathlib.Path(__file__).resolve().parents[2]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--scene", default=str(ROOT / "scenes" / "soft_shadows.json"))
    ap.add_argument("--width", type=int, default=160)
    ap.add_argument("--height", type=int, default=100)
    ap.add_argument("--max-spp", type=int, default=64)
    ap.add_argument("--reference-spp", type=int, default=1024)
    ap.add_argument("--threads", type=int, default=None)
    ap.add_argument("-o", "--output", default="error_vs_time.png")
    a = ap.parse_args()

    scene = glint.load_scene(a.scene)
    size = dict(width=a.width, height=a.height, threads=a.threads)
    # The reference: the same frame with many more samples (another seed, so that its noise is
    # independent of every curve's).
    reference = scene.render(spp=a.reference_spp, seed=1000, sampler="sobol", **size)

    curves = {}
    spps = [1 << k for k in range(a.max_spp.bit_length()) if 1 << k <= a.max_spp]
    for sampler in ("random", "stratified", "sobol"):
        points = []
        for spp in spps:
            frame = scene.render(spp=spp, seed=1, sampler=sampler, **size)
            points.append((frame.stats["seconds"], glint.compare(frame, reference)["rmse"]))
        curves[sampler] = points
        print(sampler, " ".join(f"{s:.3f}s:{e:.4g}" for s, e in points), flush=True)

    # Adaptive sampling: each target halves the last; samples go where the noise is, up to
    # --max-spp. The first target is the error the uniform stratified frame had at 4 spp.
    target = curves["stratified"][min(2, len(spps) - 1)][1]
    points = []
    for _ in range(5):
        frame = scene.render(target_rmse=target, max_spp=a.max_spp, seed=1, **size)
        points.append((frame.stats["seconds"], glint.compare(frame, reference)["rmse"]))
        target /= 2
    curves["adaptive (stratified)"] = points
    print("adaptive", " ".join(f"{s:.3f}s:{e:.4g}" for s, e in points), flush=True)

    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    for name, points in curves.items():
        seconds, errors = zip(*points)
        ax.loglog(seconds, errors, "o-", label=name)
    ax.set_xlabel("render time (s)")
    ax.set_ylabel("RMSE against the reference")
    ax.set_title(f"{pathlib.Path(a.scene).name}, {a.width}x{a.height}")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(a.output, dpi=120)
    print("wrote", a.output)


if __name__ == "__main__":
    sys.exit(main())

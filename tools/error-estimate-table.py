#!/usr/bin/env python3
"""How well a render's own error estimate matches its true error (docs/validation.md, "Error
estimate"), and what adaptive sampling buys (docs/validation.md, "Adaptive sampling against
uniform sampling").

estimate: for each bundled scene, an independent reference (another seed) at 64x the largest
sample count, then renders at each sample count; each row gives the render's estimated RMSE
(--stats-json: estimated_rmse), its true RMSE against the reference (`glint compare`), and their
ratio. The reference's own variance adds 1/64 of the render's at the largest count (RMSE
+0.8 %) and less below it.

adaptive: for each scene, uniform renders at a ladder of sample counts and adaptive renders at a
ladder of --target-rmse, each against one reference; the time each needs to reach a given true
RMSE (interpolated in log-log between the ladder's points) and their ratio, and the same ratio
of mean samples per pixel ("samples saved": what the allocation buys) and of rays traced ("rays
saved": the work it buys), both free of timing noise.

With --paired-runs R, each level is then also timed head to head: the --target-rmse at which
adaptive sampling's true RMSE reaches uniform's (interpolated log-log on the adaptive ladder's
targets and true errors) is rendered once to measure that error, and then R times alternately
with the uniform render, so that both see the same machine; the table gives the ratio of their
fastest and the median of the pairs' ratios, with adaptive's time scaled to uniform's error along
the adaptive ladder's rays (a local slope, free of timing noise).

Prints markdown tables; writes images and JSON under --out.
"""

import argparse
import json
import math
import statistics
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def glint(args, binary):
    subprocess.run([binary] + args, check=True, stdout=subprocess.DEVNULL)


def render(binary, scene, out, size, seed, spp, extra=()):
    stats = out.with_suffix(".json")
    glint(["render", str(scene), "-o", str(out), "--quiet", "--width", str(size[0]), "--height",
           str(size[1]), "--seed", str(seed), "--spp", str(spp), "--stats-json", str(stats),
           *extra], binary)
    return json.loads(stats.read_text())


def compare(binary, image, reference):
    out = image.with_suffix(".cmp.json")
    glint(["compare", str(image), str(reference), "--json", str(out)], binary)
    return json.loads(out.read_text())


def scenes(names):
    every = sorted(p for p in (ROOT / "scenes").glob("*.json"))
    return [p for p in every if not names or p.stem in names]


def estimate_table(args):
    print("| scene | spp | estimated RMSE | true RMSE | ratio |")
    print("|---|---:|---:|---:|---:|")
    worst = 1.0
    for scene in scenes(args.scenes):
        ref = args.out / f"{scene.stem}-ref.exr"
        render(args.glint, scene, ref, args.size, 7919, 64 * max(args.spp))
        for spp in args.spp:
            img = args.out / f"{scene.stem}-{spp}.exr"
            st = render(args.glint, scene, img, args.size, 1, spp)
            true = compare(args.glint, img, ref)["rmse"]
            est = st["estimated_rmse"]
            ratio = est / true if true > 0 else float("nan")
            worst = max(worst, ratio, 1 / ratio) if ratio == ratio else worst
            print(f"| {scene.stem} | {spp} | {est:.3g} | {true:.3g} | {ratio:.2f} |", flush=True)
    print(f"\nworst ratio (either way): {worst:.2f}")


def time_to(points, target):
    """Seconds at which the (seconds, rmse) ladder reaches `target`, log-log interpolated."""
    points = sorted(points)
    for (t0, e0), (t1, e1) in zip(points, points[1:]):
        if e0 >= target >= e1 and e0 > e1:
            f = (math.log(e0) - math.log(target)) / (math.log(e0) - math.log(e1))
            return math.exp(math.log(t0) + f * (math.log(t1) - math.log(t0)))
    return None


def log_interpolate(points, x):
    """y at x on the (x, y) polyline through `points`, log-log, extrapolated from the nearest
    segment at either end. Points of an x already seen are dropped (targets loose enough that
    every pixel stops at --min-spp give the same render, hence the same error)."""
    distinct = {}
    for px, py in sorted(points):
        distinct.setdefault(px, py)
    points = sorted(distinct.items())
    if len(points) < 2:
        sys.exit(f"error-estimate-table: {len(points)} distinct point(s) to interpolate at {x:.3g}: "
                 "widen the ladder")
    for (x0, y0), (x1, y1) in zip(points, points[1:]):
        if x <= x1 or (x1, y1) == points[-1]:
            f = (math.log(x) - math.log(x0)) / (math.log(x1) - math.log(x0))
            return math.exp(math.log(y0) + f * (math.log(y1) - math.log(y0)))


def paired_times(args, scene, ref, levels, adaptive_targets, adaptive_rays):
    """For each (spp, uniform true RMSE) level: the fastest and median time of the uniform
    render and of the adaptive one at the target that reaches the same error, run alternately."""
    rows = []
    for spp, goal in levels:
        # Targets and errors both fall along the ladder: the target whose error is the goal.
        target = log_interpolate([(e, t) for t, e in adaptive_targets], goal)
        extra = ["--target-rmse", f"{target:.6g}", "--min-spp", str(args.min_spp)]
        uimg, aimg = args.out / f"{scene.stem}-pu{spp}.exr", args.out / f"{scene.stem}-pa{spp}.exr"
        render(args.glint, scene, aimg, args.size, 1, args.max_spp, extra)
        reached = compare(args.glint, aimg, ref)["rmse"]
        # Rays needed for an error fall as a power of it; its local exponent along the ladder.
        rays_at = lambda e: log_interpolate([(err, r) for r, err in adaptive_rays], e)
        scale = rays_at(goal) / rays_at(reached)
        tu, ta = [], []
        for _ in range(args.paired_runs):
            tu.append(render(args.glint, scene, uimg, args.size, 1, spp)["seconds"])
            ta.append(render(args.glint, scene, aimg, args.size, 1, args.max_spp, extra)["seconds"]
                      * scale)
        rows.append((spp, goal, reached / goal, min(tu), min(ta), min(tu) / min(ta),
                     statistics.median(u / a for u, a in zip(tu, ta))))
    return rows


def adaptive_table(args):
    print("| scene | true RMSE | uniform s | adaptive s | speed-up | samples saved | rays saved |")
    print("|---|---:|---:|---:|---:|---:|---:|")
    paired = []
    for scene in scenes(args.scenes):
        ref = args.out / f"{scene.stem}-aref.exr"
        render(args.glint, scene, ref, args.size, 7919, args.reference_spp)
        # (seconds, rmse), (mean samples per pixel, rmse) and (rays traced, rmse) of each render
        uniform, adaptive, uniform_spp, adaptive_spp, uniform_rays, adaptive_rays = ([] for _ in range(6))
        adaptive_targets = []  # (target, true RMSE)
        for spp in args.ladder:
            for _ in range(args.runs):
                img = args.out / f"{scene.stem}-u{spp}.exr"
                st = render(args.glint, scene, img, args.size, 1, spp)
                e = compare(args.glint, img, ref)["rmse"]
                uniform.append((st["seconds"], e))
                uniform_spp.append((spp, e))
                uniform_rays.append((st["rays_total"], e))
        # The target is met with slack (ErrorTarget::ratio: the frame's error reaches the mean
        # of the pixels' sigma*sqrt(c) over their root mean square times it): targets from 4x the
        # largest uniform error down past an eighth of the smallest, in steps of sqrt(2), so the
        # two ladders overlap.
        target = 4 * max(e for _, e in uniform)
        while target > min(e for _, e in uniform) / 8:
            img = args.out / f"{scene.stem}-a{target:.3g}.exr"
            st = render(args.glint, scene, img, args.size, 1, args.max_spp,
                        ["--target-rmse", f"{target:.6g}", "--min-spp", str(args.min_spp)])
            e = compare(args.glint, img, ref)["rmse"]
            adaptive.append((st["seconds"], e))
            adaptive_targets.append((target, e))
            adaptive_spp.append((st["passes"][-1]["mean_spp"], e))
            adaptive_rays.append((st["rays_total"], e))
            target /= math.sqrt(2)
        for spp in args.ladder[1:-1]:
            goal = next(e for (t, e), s in zip(uniform[:: args.runs], args.ladder) if s == spp)
            tu, ta = time_to(uniform, goal), time_to(adaptive, goal)
            nu, na = time_to(uniform_spp, goal), time_to(adaptive_spp, goal)
            ru, ra = time_to(uniform_rays, goal), time_to(adaptive_rays, goal)
            saved = f"{nu / na:.2f}" if nu and na else "not reached"
            saved += f" | {ru / ra:.2f}" if ru and ra else " | not reached"
            if tu and ta:
                print(f"| {scene.stem} | {goal:.3g} | {tu:.3f} | {ta:.3f} | {tu / ta:.2f} | {saved} |",
                      flush=True)
            else:
                print(f"| {scene.stem} | {goal:.3g} | {tu} | {ta} | not reached | {saved} |",
                      flush=True)
        if args.paired_runs:
            levels = [(spp, e) for (spp, e) in uniform_spp[:: args.runs] if spp in args.ladder[1:-1]]
            paired += [(scene.stem, *row) for row in
                       paired_times(args, scene, ref, levels, adaptive_targets, adaptive_rays)]
    if paired:
        print(f"\nPaired, {args.paired_runs} runs each (> 1: adaptive is faster):\n")
        print("| scene | spp | true RMSE | adaptive RMSE / it | uniform s, fastest | adaptive s, fastest"
              " | ratio of fastest | median of pairs |")
        print("|---|---:|---:|---:|---:|---:|---:|---:|")
        for name, spp, goal, off, tu, ta, fastest, median in paired:
            print(f"| {name} | {spp} | {goal:.3g} | {off:.3f} | {tu:.3f} | {ta:.3f} | {fastest:.2f} "
                  f"| {median:.2f} |")


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("table", choices=["estimate", "adaptive"])
    p.add_argument("--glint", default=str(ROOT / "build/bin/glint"))
    p.add_argument("--out", type=Path, default=Path("/tmp/glint-error-estimate"))
    p.add_argument("--size", type=int, nargs=2, default=[80, 60])
    p.add_argument("--spp", type=int, nargs="+", default=[4, 16, 64, 256])
    p.add_argument("--scenes", nargs="*", default=[])
    p.add_argument("--ladder", type=int, nargs="+", default=[4, 8, 16, 32, 64, 128])
    p.add_argument("--reference-spp", type=int, default=4096)
    p.add_argument("--max-spp", type=int, default=1024)
    p.add_argument("--min-spp", type=int, default=8)
    p.add_argument("--runs", type=int, default=1)
    p.add_argument("--paired-runs", type=int, default=0)
    args = p.parse_args()
    args.out.mkdir(parents=True, exist_ok=True)
    (estimate_table if args.table == "estimate" else adaptive_table)(args)


if __name__ == "__main__":
    sys.exit(main())

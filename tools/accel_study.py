#!/usr/bin/env python3
"""Cost per ray against the number of primitives n for every acceleration structure
(docs/acceleration.md).

Two families of scenes, n from 10^2 to 10^6 (--max-n):
  spheres  n spheres scattered uniformly in [-1, 1]^3, radius 0.25 n^(-1/3) (the same share of
           the volume at every n), seen by a camera 4 units away;
  stadium  "a teapot in a stadium": n/2 spheres packed into a ball of radius 0.5 at the centre
           (the teapot) and n/2 spheres spread over a ring 100 units across and 10 high (the
           stadium), seen from 3 units off the teapot.
For each scene `glint bench --structures` builds every structure and times one thread on the
camera rays (160 x 120) and on --rays random rays (origins in the scene's box, directions
uniform on the sphere), the best of three passes, and counts the nodes or cells each camera ray
visits and the primitives it tests (Glint's own structures; Embree's traversal is not
counted), and for ray classification what its lazy build made (cells, bytes) and its first
pass's time beside its best. Prints markdown tables; writes the plots and
the figures (JSON) to --out. Needs python3-matplotlib (Debian's /usr/bin/python3).

--only NAME,... measures only those structures and puts their figures into the JSON already in
--out (the others' are kept), so that a structure added to STRUCTURES joins the study without
measuring the rest again.
"""

import argparse
import json
import math
import random
import subprocess
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
STRUCTURES = ["embree", "bvh", "kdtree", "octree", "grid", "octree-generate-and-test", "rayclass",
              "coherence", "spheres"]


def spheres_scene(n, rng):
    r = 0.25 * n ** (-1 / 3)
    objects = [{"type": "sphere", "center": [round(rng.uniform(-1, 1), 6) for _ in range(3)],
                "radius": r, "material": "m"} for _ in range(n)]
    camera = {"eye": [0, 0, 4], "look_at": [0, 0, 0], "vfov": 40}
    return camera, objects


def stadium_scene(n, rng):
    objects = []
    teapot = n // 2
    r_teapot = 0.25 * 0.5 * teapot ** (-1 / 3)
    while len(objects) < teapot:  # uniform in a ball of radius 0.5
        p = [round(rng.uniform(-0.5, 0.5), 6) for _ in range(3)]
        if sum(c * c for c in p) <= 0.25:
            objects.append({"type": "sphere", "center": p, "radius": r_teapot, "material": "m"})
    stands = n - teapot
    for _ in range(stands):
        a = rng.uniform(0, 2 * math.pi)
        radius = rng.uniform(40, 50)
        objects.append({"type": "sphere", "radius": 0.2, "material": "m",
                        "center": [round(radius * math.cos(a), 4), round(rng.uniform(0, 10), 4),
                                   round(radius * math.sin(a), 4)]})
    camera = {"eye": [0, 0.5, 3], "look_at": [0, 0, 0], "vfov": 40}
    return camera, objects


def write_scene(path, family, n):
    rng = random.Random(n * 7 + (0 if family == "spheres" else 1))
    camera, objects = (spheres_scene if family == "spheres" else stadium_scene)(n, rng)
    scene = {"render": {"width": 160, "height": 120}, "camera": camera,
             "materials": {"m": {"type": "phong"}},
             "lights": [{"type": "point", "position": [0, 20, 10], "intensity": [1, 1, 1]}],
             "objects": objects}
    path.write_text(json.dumps(scene, separators=(",", ":")))


def coherence_study(glint, work, max_n, rays):
    """Ray coherence's preprocessing against n objects and m origins (seed 002 §9.2.4: O(m·n)
    visibility sets): the spheres family with a share of its spheres mirrors (each an origin,
    beside the eye and the light), and its query cost on the camera rays."""
    rows = []
    for share in (0, 0.01, 0.1):
        n = 100
        while n <= max_n:
            scene, figures = work / f"coherence_{share}_{n}.json", work / f"coherence_{n}.out.json"
            rng = random.Random(n * 7)
            camera, objects = spheres_scene(n, rng)
            for i, o in enumerate(objects):
                if share and i % round(1 / share) == 0:
                    o["material"] = "mirror"
            scene.write_text(json.dumps({
                "render": {"width": 160, "height": 120}, "camera": camera,
                "materials": {"m": {"type": "phong"}, "mirror": {"type": "mirror"}},
                "lights": [{"type": "point", "position": [0, 20, 10], "intensity": [1, 1, 1]}],
                "objects": objects}, separators=(",", ":")))
            subprocess.run([glint, "bench", str(scene), "--structures", "--accel", "coherence",
                            "--random-rays", str(rays), "--json", str(figures)], check=True,
                           stdout=subprocess.DEVNULL)
            c = json.loads(figures.read_text())["structures"]["coherence"]
            rows.append((share, n, c))
            scene.unlink()
            n *= 10
    print("\nray coherence: preprocessing against n and m (rows: origins within the budgets)\n")
    print("| mirrors | n | m | rows | m·n | sets computed | build s | MiB | camera ns/ray | "
          "camera tests/ray |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for share, n, c in rows:
        print(f"| {share:.0%} | {n:.0e} | {c['origins']} | {c['rows']} | "
              f"{c['origins'] * c['objects']:.1e} | {c['pairs']:.1e} | {c['build_seconds']:.3g} | "
              f"{c['bytes'] / 2**20:.2f} | {c['camera_ns_per_ray']:.0f} | "
              f"{c['camera_tests_per_ray']:.1f} |")


def plot(results, out):
    try:
        import matplotlib
    except ImportError:  # the figures and tables still come out
        print(f"matplotlib is not installed: {out}/accel_study_*.png not redrawn "
              "(redraw with --plot-only where it is)")
        return
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    figures = [("camera_steps_per_ray", "nodes or cells visited per camera ray"),
               ("camera_tests_per_ray", "primitives tested per camera ray"),
               ("camera_ns_per_ray", "ns per camera ray (1 thread)"),
               ("random_ns_per_ray", "ns per random ray (1 thread)"),
               ("build_seconds", "build seconds"), ("bytes", "bytes of the structure")]
    for family in ("spheres", "stadium"):
        fig, axes = plt.subplots(2, 3, figsize=(16, 8.4))
        axes = axes.ravel()
        for ax, (key, label) in zip(axes, figures):
            for s in STRUCTURES:
                pts = [(r["n"], r["structures"][s].get(key)) for r in results
                       if r["family"] == family and s in r.get("structures", {})]
                pts = [(n, v) for n, v in pts if v]
                if pts:  # one colour per structure in every panel (Embree has no counts)
                    ax.loglog(*zip(*pts), marker="o", label=s, color=f"C{STRUCTURES.index(s)}")
            ns = sorted({r["n"] for r in results if r["family"] == family})
            if key == "camera_steps_per_ray" and ns:
                # Glint's bound: a 3D-DDA enters at most 3R - 2 of the grid's R = ceil(cbrt n)
                # cells per axis (seed 002's eq. 9.1 writes 1 + 7(R - 1)); a balanced hierarchy
                # is log2 n levels deep.
                ax.loglog(ns, [3 * math.ceil(n ** (1 / 3) - 1e-9) - 2 for n in ns], "k:",
                          label="Glint's bound 3⌈∛n⌉ − 2")
                ax.loglog(ns, [math.log2(n) for n in ns], "k--", label="log₂ n")
                ax.legend(fontsize=8)
            elif key.endswith("ns_per_ray") and ns:
                # The same claims for time, scaled to the grid's and the BVH's first points.
                first = [r for r in results if r["family"] == family and r["n"] == ns[0]][0]
                g0, b0 = first["structures"]["grid"][key], first["structures"]["bvh"][key]
                ax.loglog(ns, [g0 * (n / ns[0]) ** (1 / 3) for n in ns], "k:", label="∝ ∛n")
                ax.loglog(ns, [b0 * math.log2(n) / math.log2(ns[0]) for n in ns], "k--",
                          label="∝ log n")
                # Seed 002 §9.2.2's E[Q(n)] = O(∛n log n) for the octree, from its first point.
                o0 = first["structures"].get("octree", {}).get(key)
                if o0:
                    ax.loglog(ns, [o0 * (n / ns[0]) ** (1 / 3) * math.log2(n) / math.log2(ns[0])
                                   for n in ns], "k-.", label="∝ ∛n log n")
            ax.set_xlabel("primitives n")
            ax.set_title(label)
            ax.grid(True, which="both", alpha=0.3)
        axes[2].legend(fontsize=8)
        fig.suptitle(f"{family}: cost against n")
        fig.tight_layout()
        fig.savefig(out / f"accel_study_{family}.png", dpi=72)
        plt.close(fig)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("--glint", default=str(ROOT / "build/bin/glint"))
    ap.add_argument("--out", default=str(ROOT / "docs/img"))
    ap.add_argument("--work", default="/tmp/glint-accel-study")
    ap.add_argument("--max-n", type=int, default=1000000)
    ap.add_argument("--rays", type=int, default=100000)
    ap.add_argument("--plot-only", metavar="JSON", help="re-plot the figures a run wrote")
    ap.add_argument("--only", metavar="NAMES",
                    help="comma-separated structures to measure into --out's accel_study.json")
    args = ap.parse_args()
    measured = args.only.split(",") if args.only else STRUCTURES
    unknown = [s for s in measured if s not in STRUCTURES]
    if unknown:
        ap.error(f"--only: unknown structure {unknown[0]!r}; known: {', '.join(STRUCTURES)}")
    out, work = Path(args.out), Path(args.work)
    out.mkdir(parents=True, exist_ok=True)
    work.mkdir(parents=True, exist_ok=True)
    if args.plot_only:
        plot(json.loads(Path(args.plot_only).read_text()), out)
        return
    previous = {}
    if args.only and (out / "accel_study.json").exists():
        previous = {(r["family"], r["n"]): r
                    for r in json.loads((out / "accel_study.json").read_text())}
    results = []
    for family in ("spheres", "stadium"):
        n = 100
        while n <= args.max_n:
            scene, figures = work / f"{family}_{n}.json", work / f"{family}_{n}.out.json"
            write_scene(scene, family, n)
            subprocess.run([args.glint, "bench", str(scene), "--structures", "--accel",
                            ",".join(measured), "--random-rays", str(args.rays), "--json",
                            str(figures)], check=True, stdout=subprocess.DEVNULL)
            r = json.loads(figures.read_text())
            if (family, n) in previous:
                kept = previous[(family, n)]
                kept["structures"].update(r["structures"])
                r = kept
            r.update(family=family, n=n)
            results.append(r)
            scene.unlink()
            n *= 10
    (out / "accel_study.json").write_text(json.dumps(results, indent=1))
    plot(results, out)
    for key, label in (("camera_steps_per_ray", "nodes or cells visited per camera ray"),
                       ("camera_tests_per_ray", "primitives tested per camera ray"),
                       ("random_steps_per_ray", "nodes or cells visited per random ray"),
                       ("random_tests_per_ray", "primitives tested per random ray"),
                       ("random_ns_per_ray", "ns per random ray"),
                       ("camera_ns_per_ray", "ns per camera ray"),
                       ("camera_first_pass_ns_per_ray",
                        "ns per camera ray, first pass (with what is built while tracing)"),
                       ("build_seconds", "build s"), ("bytes", "MiB")):
        print(f"\n{label}\n\n| scene | n | " + " | ".join(STRUCTURES) + " |")
        print("|---|---|" + "---|" * len(STRUCTURES))
        for r in results:
            vals = [r["structures"].get(s, {}).get(key) for s in STRUCTURES]
            fmt = (lambda v: f"{v / 2**20:.2f}") if key == "bytes" else (
                (lambda v: f"{v:.3g}") if key == "build_seconds" else (
                    (lambda v: f"{v:.1f}") if "steps" in key or "tests" in key else (
                        lambda v: f"{v:.0f}")))
            fmt = (lambda f: lambda v: "–" if v is None else f(v))(fmt)
            print(f"| {r['family']} | {r['n']:.0e} | " + " | ".join(fmt(v) for v in vals) + " |")
    # Ray classification builds while tracing: its candidate lists and what the lazy build made,
    # beside the seed's claims (short lists; the cost of making a cell amortised over its rays).
    print("\nrayclass: candidate list and lazy build\n\n| scene | n | camera cells descended | "
          "camera list (tests) | random list | cells after camera | MiB after camera | "
          "cells after random | MiB after random | camera ns first pass / best | "
          "random ns first pass / best |")
    print("|---|---|" + "---|" * 9)
    for r in results:
        rc = r["structures"].get("rayclass")
        if not rc:
            continue
        cam, rnd = rc["lazy"]["after_camera"], rc["lazy"]["after_random"]
        print(f"| {r['family']} | {r['n']:.0e} | {rc['camera_steps_per_ray']:.1f} | "
              f"{rc['camera_tests_per_ray']:.1f} | {rc['random_tests_per_ray']:.1f} | "
              f"{cam['cells']} | {cam['bytes'] / 2**20:.2f} | {rnd['cells']} | "
              f"{rnd['bytes'] / 2**20:.2f} | {rc['camera_first_pass_ns_per_ray']:.0f} / "
              f"{rc['camera_ns_per_ray']:.0f} | {rc['random_first_pass_ns_per_ray']:.0f} / "
              f"{rc['random_ns_per_ray']:.0f} |")
    coherence_study(args.glint, work, min(args.max_n, 100000), args.rays)


if __name__ == "__main__":
    main()

#!/usr/bin/env python3
"""Glint against POV-Ray 3.7 and Embree's `pathtracer`, in one run (docs/peers.md).

1. scenes/peers/whitted_area_dof.{json,pov}: the same Whitted scene with a quad area light and
   focal blur in both renderers. Each renderer renders a converged reference of its own, then a
   ladder of matched sample counts (camera samples x light samples); every image is compared
   with its own renderer's reference (`glint compare`), and the two references with each other
   (a check that the scenes match). Ladder runs are repeated and interleaved (Glint, POV-Ray,
   Glint, ...) so that load from other processes hits both alike; the table gives median wall
   and CPU seconds (user + system of the process: the steadier figure on a shared machine).
2. Extra rows: POV-Ray with its adaptive shortcuts on (area light `adaptive 0`, focal blur
   `variance 1/128`), Glint with the plain random sampler (what the stratified sampler costs),
   Glint alone at more camera sample counts, and Glint with adaptive sampling to a ladder of
   `--target-rmse` values. Then, for each POV-Ray row, Glint's wall time to reach that row's
   error against its own reference: log-log interpolation along each Glint series (uniform at
   one light sample count, or adaptive), never extrapolated, the best series taken.
3. Embree's `pathtracer` on its cornell_box, and Glint on the same mesh and camera
   (scenes/peers/cornell_box.json): wall time and rays, counted with an LD_PRELOAD shim
   (tools/peers/count_embree_rays.c) around rtcIntersect1 / rtcOccluded1 and their streams
   (rtcIntersect1M / rtcOccluded1M, which Glint uses for camera rays).

Prints markdown tables and writes everything (images, JSON, the tables) under --out.
Needs: povray (Debian package povray), and for part 3 embree-tools and a C compiler.
"""

import argparse
import json
import math
import os
import re
import resource
import shutil
import statistics
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
SCENE_JSON = ROOT / "scenes/peers/whitted_area_dof.json"
SCENE_POV = ROOT / "scenes/peers/whitted_area_dof.pov"
CORNELL_JSON = ROOT / "scenes/peers/cornell_box.json"
CORNELL_ECS = Path("/usr/share/doc/embree3/models/cornell_box.ecs")
SHIM_SRC = ROOT / "tools/peers/count_embree_rays.c"


def parse_config(text):
    """'16x4' -> (camera samples 16, light samples 4); light samples must be 4, 16, 64, ..."""
    m = re.fullmatch(r"(\d+)x(\d+)", text.strip())
    if not m:
        raise argparse.ArgumentTypeError(f"expected SPPxLIGHT, e.g. 16x4, got {text!r}")
    spp, light = int(m.group(1)), int(m.group(2))
    n = round(light ** 0.5)
    if n * n != light or n < 2 or n & (n - 1):
        raise argparse.ArgumentTypeError(
            f"light samples must be the square of a power of two >= 2 (4, 16, 64, ...), got {light}"
            " (POV-Ray's area-light grid is n x n and weighs points equally only for n = 2^k)")
    return spp, light


def configs(text):
    return [parse_config(t) for t in text.split(",") if t.strip()]


def cpu_of_children():
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


LAST_CPU = [0.0]  # CPU seconds (user + system) of the last command run


def run(cmd, cwd=None, env=None, timeout=1800):
    """Runs one command to the end; returns its wall seconds and output. Its CPU seconds go to
    LAST_CPU (the commands run one at a time, so the children's rusage delta is this one's)."""
    c0, t0 = cpu_of_children(), time.perf_counter()
    p = subprocess.run(cmd, cwd=cwd, env=env, capture_output=True, text=True, timeout=timeout)
    wall = time.perf_counter() - t0
    LAST_CPU[0] = cpu_of_children() - c0
    if p.returncode != 0:
        sys.stderr.write(p.stdout + p.stderr)
        raise SystemExit(f"failed ({p.returncode}): {' '.join(map(str, cmd))}")
    return wall, p.stdout + p.stderr


class Peers:
    def __init__(self, args):
        self.a = args
        self.out = Path(args.out).resolve()
        self.out.mkdir(parents=True, exist_ok=True)
        self.glint = str(Path(args.glint).resolve())
        self.scene_text = SCENE_JSON.read_text()
        self.results = {"runs": [], "load_average": {}, "args": vars(args)}

    # ---- renderers -------------------------------------------------------------------------
    def glint_scene(self, light):
        path = self.out / f"glint_light{light}.json"
        text, n = re.subn(r'"samples":\s*\d+', f'"samples": {light}', self.scene_text)
        if n != 1:
            raise SystemExit(f"{SCENE_JSON}: expected exactly one \"samples\" key, found {n}")
        path.write_text(text)
        return path

    def render_glint(self, spp, light, tag, sampler=None, target=None):
        exr = self.out / f"{tag}.exr"
        stats = self.out / f"{tag}.stats.json"
        cmd = [self.glint, "render", str(self.glint_scene(light)), "-o", str(exr),
               "--threads", str(self.a.threads), "--spp", str(spp), "--width", str(self.a.width),
               "--height", str(self.a.height), "--quiet", "--stats-json", str(stats)]
        if sampler:
            cmd += ["--sampler", sampler]
        if target:
            cmd += ["--target-rmse", f"{target:g}"]
        wall, _ = run(cmd)
        s = json.loads(stats.read_text())
        return {"exr": str(exr), "wall": wall, "cpu": LAST_CPU[0], "inner": s["seconds"],
                "rays": s["rays_total"]}

    def render_pov(self, spp, light, tag, adaptive=False):
        exr = f"{tag}.exr"
        n = round(light ** 0.5)
        cmd = ["povray", f"+I{SCENE_POV}", f"+O{exr}", "+FE", f"+W{self.a.width}",
               f"+H{self.a.height}", "-A", f"+WT{self.a.threads}", "-D", "-P", "-V",
               f"Declare=NB={spp}", f"Declare=NL={n}"]
        if adaptive:
            cmd += ["Declare=ADAPT=0", "Declare=VAR=0.0078125"]
        wall, log = run(cmd, cwd=self.out)  # POV-Ray may write only below its working directory

        def stat(pattern):
            m = re.search(pattern, log)
            return float(m.group(1)) if m else None

        rays = (stat(r"\nRays:\s+(\d+)") or 0) + (stat(r"Shadow Ray Tests:\s+(\d+)") or 0)
        return {"exr": str(self.out / exr), "wall": wall, "cpu": LAST_CPU[0],
                "inner": stat(r"Trace Time:.*\(([\d.]+) seconds\)"), "rays": int(rays)}

    def compare(self, image, reference, name, diff=False):
        js = self.out / f"compare_{name}.json"
        cmd = [self.glint, "compare", image, reference, "--json", str(js)]
        if diff:
            cmd += ["--diff", str(self.out / f"diff_{name}.png")]
        run(cmd)
        return json.loads(js.read_text())

    # ---- part 1 and 2 ----------------------------------------------------------------------
    def povray_part(self):
        a = self.a
        self.results["load_average"]["start"] = os.getloadavg()
        rspp, rlight = a.reference
        print(f"references: {rspp} camera x {rlight} light samples", file=sys.stderr)
        kept = self.out / "references.json"
        if a.keep_references and kept.exists() and json.loads(kept.read_text())["config"] == [
                rspp, rlight]:
            ref = json.loads(kept.read_text())["references"]  # images and timings of a previous run
            print("  kept from a previous run", file=sys.stderr)
        else:
            ref = {"glint": self.render_glint(rspp, rlight, "glint_reference"),
                   "povray": self.render_pov(rspp, rlight, "povray_reference")}
            kept.write_text(json.dumps({"config": [rspp, rlight], "references": ref}, indent=1))
        self.results["references"] = ref
        self.results["cross"] = self.compare(ref["povray"]["exr"], ref["glint"]["exr"],
                                             "povray_vs_glint_references", diff=True)

        jobs = []
        for spp, light in a.ladder:
            jobs.append(("glint", spp, light, {}))
            jobs.append(("povray", spp, light, {}))
        for spp, light in a.extra:
            jobs.append(("povray adaptive", spp, light, {"adaptive": True}))
            jobs.append(("glint random sampler", spp, light, {"sampler": "random"}))
        for spp, light in a.glint_only:
            jobs.append(("glint", spp, light, {}))
        for target in a.adaptive_targets:
            jobs.append((f"glint adaptive {target:g}", a.adaptive_max_spp, a.adaptive_light,
                         {"target": target}))
        # Fixed costs: process start, parse, build, write; an 8x6 image with one sample.
        tiny = {"glint": [self.glint, "render", str(self.glint_scene(4)), "-o",
                          str(self.out / "glint_tiny.exr"), "--threads", str(a.threads), "--spp",
                          "1", "--width", "8", "--height", "6", "--quiet"],
                "povray": ["povray", f"+I{SCENE_POV}", "+Opovray_tiny.exr", "+FE", "+W8", "+H6",
                           "-A", f"+WT{a.threads}", "-D", "-P", "-V", "Declare=NB=1",
                           "Declare=NL=2"]}
        self.results["startup"] = {}
        for name, cmd in tiny.items():
            walls, cpus = [], []
            for _ in range(3):
                walls.append(run(cmd, cwd=self.out)[0])
                cpus.append(LAST_CPU[0])
            self.results["startup"][name] = {"wall": statistics.median(walls),
                                             "cpu": statistics.median(cpus)}
        for rep in range(a.reps):
            order = jobs if rep % 2 == 0 else list(reversed(jobs))
            for renderer, spp, light, kw in order:
                tag = f"{renderer.replace(' ', '_')}_{spp}x{light}"
                print(f"rep {rep + 1}/{a.reps}: {renderer} {spp}x{light}", file=sys.stderr)
                if renderer.startswith("glint"):
                    r = self.render_glint(spp, light, tag, **kw)
                else:
                    r = self.render_pov(spp, light, tag, **kw)
                own = ref["glint" if renderer.startswith("glint") else "povray"]["exr"]
                if rep == 0:  # the images are the same in every repetition
                    e = self.compare(r["exr"], own, tag)
                    r.update(rmse=e["rmse"], relmse=e["relmse"])
                r.update(renderer=renderer, spp=spp, light=light, rep=rep,
                         target=kw.get("target"))
                self.results["runs"].append(r)
        self.results["load_average"]["end"] = os.getloadavg()

    # ---- part 3 ----------------------------------------------------------------------------
    def embree_part(self):
        a = self.a
        if not shutil.which("pathtracer") or not CORNELL_ECS.exists():
            print("embree-tools not installed: skipping pathtracer "
                  "(apt-get install embree-tools)", file=sys.stderr)
            return
        shim = self.out / "count_embree_rays.so"
        cc = shutil.which("cc") or shutil.which("gcc")
        if cc:
            run([cc, "-O2", "-shared", "-fPIC", "-o", str(shim), str(SHIM_SRC), "-ldl"])
        rows = []

        def counted(cmd):
            """Wall seconds, (intersect, occluded) rays and CPU seconds of each repetition; the
            shim costs a thread-local increment per ray."""
            env = dict(os.environ, LD_PRELOAD=str(shim)) if cc else None
            walls, rays, cpus = [], [], []
            for _ in range(a.reps):
                wall, log = run(cmd, env=env)
                m = re.search(r"embree-rays intersect1 (\d+) occluded1 (\d+)", log)
                walls.append(wall)
                cpus.append(LAST_CPU[0])
                rays.append((int(m.group(1)), int(m.group(2))) if m else None)
            return walls, rays, cpus

        pt = ["pathtracer", "-c", str(CORNELL_ECS), "--spp", "16", "--threads", str(a.threads)]
        for label, extra in (("pathtracer (default: --max-path-length 8)", []),
                             ("pathtracer --max-path-length 1", ["--max-path-length", "1"])):
            print(f"embree: {label}", file=sys.stderr)
            walls, rays, cpus = counted(pt + extra + ["-o", str(self.out / "pathtracer.pfm")])
            rows.append({"program": label, "walls": walls, "rays": rays, "cpus": cpus})
        print("embree: glint cornell_box", file=sys.stderr)
        stats = self.out / "glint_cornell.stats.json"
        cmd = [self.glint, "render", str(CORNELL_JSON), "-o", str(self.out / "glint_cornell.exr"),
               "--threads", str(a.threads), "--quiet", "--stats-json", str(stats)]
        walls, rays, cpus = counted(cmd)
        inner = json.loads(stats.read_text())["seconds"]
        rows.append({"program": "glint render (camera + shadow ray)", "walls": walls, "rays": rays,
                     "cpus": cpus, "inner": inner})
        _, log = run([self.glint, "bench", str(CORNELL_JSON), "--accel", "embree", "--threads",
                      str(a.threads), "--render-runs", "0"])
        self.results["embree"] = {"rows": rows, "glint_bench": log}

    # ---- time to POV-Ray's error -----------------------------------------------------------
    @staticmethod
    def time_to_error(points, goal):
        """The wall time at which a series of (work, wall s, RMSE) points, in order of the work
        asked for (samples, or a falling target), first reaches RMSE `goal`: log-log
        interpolation between that point and the one before it; None where the first point
        already reaches it or none does (never extrapolated). A series whose times or errors do
        not fall and rise in step with the work is reported, not smoothed over."""
        pts = sorted(points)
        if any(b[1] < a[1] or b[2] > a[2] for a, b in zip(pts, pts[1:])):
            print(f"warning: a Glint series is not monotone in time and error: {pts}",
                  file=sys.stderr)
        for k, (_, t1, e1) in enumerate(pts):
            if e1 <= goal:
                if k == 0:
                    return None
                _, t0, e0 = pts[k - 1]
                f = math.log(e0 / goal) / math.log(e0 / e1)
                return math.exp(math.log(t0) + f * math.log(t1 / t0))
        return None

    def time_to_povray_error(self, groups):
        """For each POV-Ray row, Glint's wall time (medians over the repetitions) to reach its
        RMSE along each Glint series: uniform at each light sample count, and adaptive."""
        series = {}
        for (renderer, spp, light), rs in groups.items():
            if renderer == "glint":
                name, work = f"uniform, light {light}", spp
            elif renderer.startswith("glint adaptive"):
                name, work = "adaptive", 1 / rs[0]["target"]
            else:
                continue
            series.setdefault(name, []).append(
                (work, statistics.median(r["wall"] for r in rs), rs[0]["rmse"]))
        names = sorted(series)
        lines = ["", "Time to POV-Ray's error: Glint's wall time (median) to reach each POV-Ray "
                 "row's RMSE against its own reference, interpolated log-log along each Glint "
                 "series (— where the series does not reach or bracket it)", "",
                 "| POV-Ray row | its RMSE | its wall s | " +
                 " | ".join(f"Glint {n} s" for n in names) + " | POV-Ray s / best Glint s |",
                 "|---|---|---|" + "---|" * len(names) + "---|"]
        rows = []
        for (renderer, spp, light), rs in groups.items():
            if not renderer.startswith("povray"):
                continue
            goal, wall = rs[0]["rmse"], statistics.median(r["wall"] for r in rs)
            times = {n: self.time_to_error(series[n], goal) for n in names}
            known = [t for t in times.values() if t]
            best = min(known) if known else None
            rows.append({"povray": f"{renderer} {spp}x{light}", "rmse": goal, "wall": wall,
                         "glint": times, "ratio": wall / best if best else None})
            cells = " | ".join(f"{times[n]:.2f}" if times[n] else "—" for n in names)
            ratio = f"{wall / best:.1f}" if best else "—"
            lines.append(f"| {renderer} {spp} x {light} | {goal:.5f} | {wall:.2f} | {cells} | "
                         f"{ratio} |")
        self.results["time_to_povray_error"] = rows
        return lines

    # ---- report ----------------------------------------------------------------------------
    def report(self):
        res, lines = self.results, []
        la = res["load_average"]
        lines.append(f"{self.a.width}x{self.a.height}, {self.a.threads} threads, "
                     f"{self.a.reps} repetitions, load average {la['start'][0]:.2f} at the start, "
                     f"{la['end'][0]:.2f} at the end (1-minute)")
        lines.append("")
        lines.append("| renderer | camera x light samples | shadow rays / pixel¹ | wall s (median) "
                     "| wall s (min–max) | CPU s² | own timer s³ | rays⁴ | Mrays/s | RMSE vs own ref "
                     "| relMSE vs own ref |")
        lines.append("|---|---|---|---|---|---|---|---|---|---|---|")
        groups = {}
        for r in res["runs"]:
            groups.setdefault((r["renderer"], r["spp"], r["light"]), []).append(r)
        for (renderer, spp, light), rs in groups.items():
            walls = [r["wall"] for r in rs]
            med = statistics.median(walls)
            first = rs[0]
            rate = first["rays"] / med / 1e6 if first["rays"] else float("nan")
            inner = statistics.median(r["inner"] or 0 for r in rs)
            cpu = statistics.median(r["cpu"] for r in rs)
            lines.append(f"| {renderer} | {spp} x {light} | {spp * light} | {med:.2f} | "
                         f"{min(walls):.2f}–{max(walls):.2f} | {cpu:.2f} | {inner:.2f} | "
                         f"{first['rays'] / 1e6:.1f} M | {rate:.1f} | "
                         f"{first['rmse']:.5f} | {first['relmse']:.6f} |")
        for name, r in res["references"].items():
            lines.append(f"| {name} reference | {self.a.reference[0]} x {self.a.reference[1]} | "
                         f"{self.a.reference[0] * self.a.reference[1]} | {r['wall']:.2f} | | "
                         f"{r['cpu']:.2f} | {r['inner'] or 0:.2f} | {r['rays'] / 1e6:.0f} M | "
                         f"{r['rays'] / r['wall'] / 1e6:.1f} | | |")
        lines += self.time_to_povray_error(groups)
        st = res["startup"]
        lines.append("")
        lines.append(f"Fixed cost (8x6 pixels, 1 sample, median of 3): Glint {st['glint']['wall']:.2f} "
                     f"s wall, {st['glint']['cpu']:.2f} s CPU; POV-Ray {st['povray']['wall']:.2f} s "
                     f"wall, {st['povray']['cpu']:.2f} s CPU")
        c = res["cross"]
        lines.append("")
        lines.append(f"POV-Ray reference against Glint reference: RMSE {c['rmse']:.5f}, relMSE "
                     f"{c['relmse']:.6f}, mean abs {c['mae']:.5f}, max abs {c['max_abs']:.4f}, "
                     f"{100 * c['share_above_threshold']:.1f} % of pixels over 0.01")
        if "embree" in res:
            lines.append("")
            lines.append("| program (cornell_box, 512x512, 16 spp) | wall s (median) | CPU s "
                         "| rays (intersect + occluded) | Mrays/s (wall) | Mrays/CPU-s |")
            lines.append("|---|---|---|---|---|---|")
            for row in res["embree"]["rows"]:
                med = statistics.median(row["walls"])
                if all(row["rays"]):
                    n = [sum(r) for r in row["rays"]]
                    i = statistics.median(r[0] for r in row["rays"])
                    o = statistics.median(r[1] for r in row["rays"])
                    rays = f"{i / 1e6:.2f} M + {o / 1e6:.2f} M"
                    rate = f"{statistics.median(k / w for k, w in zip(n, row['walls'])) / 1e6:.1f}"
                    crate = f"{statistics.median(k / c for k, c in zip(n, row['cpus'])) / 1e6:.1f}"
                else:
                    rays, rate, crate = "?", "?", "?"
                cpu = statistics.median(row["cpus"])
                lines.append(f"| {row['program']} | {med:.2f} | {cpu:.2f} | {rays} | {rate} | "
                             f"{crate} |")
            lines.append("")
            lines.append("glint bench (Embree, bare rays):")
            lines.append("```")
            lines += [ln for ln in res["embree"]["glint_bench"].splitlines()
                      if ln.startswith(("backend", "embree"))]
            lines.append("```")
        lines.append("")
        lines.append("¹ per pixel whose camera samples all hit lit surfaces: camera x light samples")
        lines.append("² user + system CPU seconds of the process (median): less sensitive than wall "
                     "time to other processes on the machine")
        lines.append("³ Glint: render seconds (--stats-json); POV-Ray: its Trace Time (median)")
        lines.append("⁴ Glint: every ray it traces (--stats-json); POV-Ray: \"Rays\" + \"Shadow Ray "
                     "Tests\" from its statistics. Mrays/s = rays / median wall s")
        text = "\n".join(lines)
        (self.out / "table.md").write_text(text + "\n")
        (self.out / "results.json").write_text(json.dumps(res, indent=1))
        print(text)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--out", default=str(ROOT / "out/peers"), help="output folder (out/peers)")
    p.add_argument("--glint", default=os.environ.get("GLINT", str(ROOT / "build/bin/glint")),
                   help="glint binary ($GLINT, else build/bin/glint)")
    p.add_argument("--width", type=int, default=320)
    p.add_argument("--height", type=int, default=240)
    p.add_argument("--threads", type=int, default=2)
    p.add_argument("--ladder", type=configs, default=configs("4x4,4x16,16x4,16x16,64x4"),
                   help="camera x light samples to compare (4x4,4x16,16x4,16x16,64x4)")
    p.add_argument("--extra", type=configs, default=configs("16x16,64x4"),
                   help="where to add POV-Ray adaptive and Glint random-sampler rows")
    p.add_argument("--glint-only", type=configs, default=configs("1x4,2x4,8x4,32x4"),
                   help="more uniform Glint runs, so that its series bracket POV-Ray's errors "
                        "(1x4,2x4,8x4,32x4)")
    p.add_argument("--adaptive-targets", type=lambda t: [float(x) for x in t.split(",") if x],
                   default=[0.028, 0.02, 0.014, 0.01],
                   help="--target-rmse values of Glint's adaptive runs (0.028,0.02,0.014,0.01; none: '')")
    p.add_argument("--adaptive-light", type=int, default=4,
                   help="light samples of the adaptive runs (4)")
    p.add_argument("--adaptive-max-spp", type=int, default=1024,
                   help="--spp (the most a pixel may take) of the adaptive runs (1024)")
    p.add_argument("--reference", type=parse_config, default=parse_config("1024x4"),
                   help="the converged references (1024x4)")
    p.add_argument("--reps", type=int, default=3, help="repetitions of each timed run (3)")
    p.add_argument("--keep-references", action="store_true",
                   help="reuse the references of a previous run in --out (same --reference)")
    p.add_argument("--no-embree", action="store_true", help="skip the pathtracer part")
    a = p.parse_args()
    if a.width * 3 != a.height * 4:
        p.error("the .pov file assumes a 4:3 image")
    if not shutil.which("povray"):
        raise SystemExit("povray not found: apt-get install povray")
    if not Path(a.glint).exists():
        raise SystemExit(f"{a.glint} not found: build Glint first (tools/render-default.sh)")
    peers = Peers(a)
    t0 = time.perf_counter()
    peers.povray_part()
    if not a.no_embree:
        peers.embree_part()
    peers.results["total_seconds"] = time.perf_counter() - t0
    peers.report()
    print(f"\n(total {peers.results['total_seconds']:.0f} s; files in {peers.out})")


if __name__ == "__main__":
    main()

#!/usr/bin/env python3
"""Projects a render's parallel efficiency at many threads from its timing at few
(docs/performance.md, "Scaling with cores"). For a machine without the cores to measure on.

    tools/project-scaling.py OUTDIR [--glint PATH] [--project 16] [--measure "1 2"] [--runs R]
                             [--scenes "default soft_shadows ..."]
                             [--adaptive SCENE "RENDER OPTIONS"]
    tools/project-scaling.py --from STATS.json [--project 16]   # one render's --stats-json
    tools/project-scaling.py OUTDIR --reuse ...   # again from the renders OUTDIR/raw holds

Each scene (and an adaptive render, by default soft_shadows --target-rmse 0.002 --max-spp 256,
as tools/scaling-study.sh) is rendered R times at each --measure thread count with --stats-json;
the run with the least "seconds" counts. Its "schedule" holds what the render did around its
parallel phases: the session's set-up on one thread, the first writes of its buffers on the
render's threads, and per phase (a pass, or adaptive sampling's probes) the time since the
phase before and each tile's seconds, in the order the threads took them. The model, from the 1-thread render:

    T(P) = setup + init / P + sum over phases (serial + loops / P + makespan_P(tiles))
           + finish + finish_loops / P
    E(P) = T1 / (P * T(P)),  T1 = T(1), the same sum for one thread

both from one 1-thread render cut into the tiles P threads take (`--tile-size`).

makespan_P is the end of the phase when P threads take its tiles in the order recorded, each
the next when it finishes one, with the tiles' 1-thread seconds (as runTiles hands them out;
each tile's thread CPU time, so that a busy machine taking the thread off its core does not
count as the tile's cost; the 1-thread render's measured seconds are shown beside T1):
the work / P plus the idle at the phase's end. "loops" are the loops over the frame's pixels
between phases (choices, tile costs, statistics, the resolved frame), which run on the
render's threads in fixed blocks; "serial" is the rest of the time between phases, on the
driving thread alone. The model leaves out what more threads do to each other (memory
bandwidth, which bounds the loops, shared caches, clock speed), so it is a projection, not a
measurement; a second efficiency counts the loops whole, as a bound. At each other --measure count it prints the measured seconds beside the model's,
and the measured idle of the phases' ends, as a check.

Writes OUTDIR/projection.md (also printed) and the stats under OUTDIR/raw. Exit status 0, 2 for
bad usage, another when a render failed.
"""
import argparse
import heapq
import json
import os
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SCENES = "default soft_shadows depth_of_field real_assets lamp_in_mirror"
ADAPTIVE = ("soft_shadows", "--target-rmse 0.002 --max-spp 256")


def tile_seconds(phase):
    """Each tile's seconds in the order taken: its thread's CPU time where noted (a busy
    machine's descheduling left out), else its wall time."""
    return [t[4] if len(t) > 4 and t[4] >= 0 else t[2] for t in phase["tiles"]]


def makespan(seconds, threads):
    """The end of a phase whose tiles, in this order, are taken by `threads` threads."""
    free = [0.0] * threads
    for s in seconds:
        heapq.heapreplace(free, free[0] + s)
    return max(free) if seconds else 0.0


def model(stats, threads, loops_scale=True):
    """What the model gives for `threads`, from a render's stats: total seconds and its parts.
    loops_scale: the loops over the frame's pixels between phases take 1/threads of their time
    (else all of it, as if they ran on one thread: a bound for loops that memory bandwidth
    limits)."""
    sch = stats["schedule"]
    serial = sch["setup_seconds"] + sch["finish_seconds"]
    loops = sch["finish_loop_seconds"]
    work = idle = 0.0
    for phase in sch["phases"]:
        seconds = tile_seconds(phase)
        span = makespan(seconds, threads)
        serial += phase["serial_seconds"]
        loops += phase["loop_seconds"]
        work += sum(seconds)
        idle += span - sum(seconds) / threads
    parallel = (sch["init_seconds"] + (loops if loops_scale else 0)) / threads
    if not loops_scale:
        serial += loops
    total = serial + parallel + work / threads + idle
    return {"total": total, "serial": serial, "loops": loops, "init": sch["init_seconds"],
            "work": work, "idle": idle}


def tile_size_at(stats, threads, requested=32):
    """The tile edge a render of these pixels takes at `threads` (effectiveTileSize)."""
    w, h = stats["schedule"]["pixels"]
    size = requested
    while size > 8 and ((w + size - 1) // size) * ((h + size - 1) // size) < 32 * threads:
        size = max(8, size // 2)
    return size


def measured_idle(stats):
    """The threads' idle at the phases' ends, as run: phase wall x threads - tile seconds."""
    sch = stats["schedule"]
    return sum(p["tiles_seconds"] * sch["threads"] - sum(t[2] for t in p["tiles"])
               for p in sch["phases"])


def render(glint, scene, threads, out, extra, reuse=False):
    if reuse and os.path.exists(out + ".json"):
        with open(out + ".json") as f:
            return json.load(f)
    cmd = [glint, "render", os.path.join(ROOT, "scenes", scene + ".json"), "-o", out + ".exr",
           "--quiet", "--threads", str(threads), "--stats-json", out + ".json"] + extra
    subprocess.run(cmd, check=True)
    with open(out + ".json") as f:
        return json.load(f)


REUSE = False


def best(glint, scene, threads, raw, name, extra, runs):
    runs_stats = [render(glint, scene, threads, os.path.join(raw, f"{name}.t{threads}.r{r}"),
                         extra, REUSE) for r in range(runs)]
    return min(runs_stats, key=lambda s: s["seconds"])


def row(label, one, cut, p, others):
    """A table row: the projection from `cut` (the 1-thread render with P threads' tiles; T1
    from `one`), and at each other count the measured seconds beside the model's from `one`."""
    m = model(cut, p)
    bound = model(cut, p, loops_scale=False)
    t1 = model(cut, 1)["total"]
    cells = [label, f"{one['seconds']:.3f} / {model(one, 1)['total']:.3f}", f"{m['serial'] * 1e3:.1f} ms",
             f"{(m['init'] + m['loops']) * 1e3:.1f} ms", f"{m['serial'] / m['total'] * 100:.1f} %",
             f"{m['idle'] / m['total'] * 100:.1f} %", f"{m['total']:.4f}",
             f"**{t1 / (p * m['total']):.3f}**", f"{t1 / (p * bound['total']):.3f}"]
    for t, s in others:
        cells.append(f"{s['seconds']:.3f} / {model(one, t)['total']:.3f}, idle "
                     f"{measured_idle(s) / (t * s['seconds']) * 100:.1f} %")
    return "| " + " | ".join(cells) + " |"


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("out", nargs="?")
    ap.add_argument("--glint", default=os.environ.get("GLINT", os.path.join(ROOT, "build/bin/glint")))
    ap.add_argument("--project", type=int, default=16)
    ap.add_argument("--measure", default="1 2")
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--scenes", default=SCENES)
    ap.add_argument("--adaptive", nargs=2, default=ADAPTIVE, metavar=("SCENE", "OPTIONS"))
    ap.add_argument("--from", dest="from_stats")
    ap.add_argument("--reuse", action="store_true",
                    help="read the renders an earlier run left in OUTDIR/raw instead of rendering")
    a = ap.parse_args()
    p = a.project
    global REUSE
    REUSE = a.reuse
    if p < 1 or a.runs < 1:
        ap.error("--project and --runs must be positive")
    if a.from_stats:
        with open(a.from_stats) as f:
            stats = json.load(f)
        m, t1 = model(stats, p), model(stats, 1)["total"]
        print(json.dumps({"threads": p, "t1": t1, "t1_measured": stats["seconds"],
                          "projected_seconds": m["total"], "efficiency": t1 / (p * m["total"]),
                          **m}, indent=1))
        return 0
    if not a.out:
        ap.error("give an output directory, or --from STATS.json")
    measure = [int(t) for t in a.measure.split()]
    if not measure or measure[0] != 1:
        ap.error("--measure must start with 1: the model projects from one thread")
    if not os.access(a.glint, os.X_OK):
        ap.error(f"no glint binary at {a.glint}")
    raw = os.path.join(a.out, "raw")
    os.makedirs(raw, exist_ok=True)
    jobs = [(s, s, []) for s in a.scenes.split()]
    jobs.append((f"{a.adaptive[0]} {a.adaptive[1]}", a.adaptive[0] + ".adaptive",
                 a.adaptive[1].split()))
    lines = ["# Scaling with cores: a projection", "",
             f"glint: {subprocess.run([a.glint, '--version'], capture_output=True, text=True).stdout.splitlines()[0]};"
             f" {os.cpu_count()} cores here; best of {a.runs} runs", "",
             f"| scene | 1 thread: measured / modelled | serial | loops | serial at {p} | end-of-pass idle at {p} "
             f"| projected seconds at {p} | projected efficiency at {p} | loops not scaling |"
             + "".join(f" measured / modelled at {t}, measured idle |" for t in measure[1:]),
             "|---|---:|---:|---:|---:|---:|---:|---:|---:|" + "---|" * (len(measure) - 1)]
    for label, name, extra in jobs:
        scene = name.split(".")[0]
        one = best(a.glint, scene, 1, raw, name, extra, a.runs)
        # The phases are modelled with the tiles P threads cut the frame into (smaller than one
        # thread's where the frame is small), T1 too, so that both come from one render.
        size = tile_size_at(one, p)
        cut = one
        if size != one["schedule"]["tile_size"]:
            cut = best(a.glint, scene, 1, raw, f"{name}.tile{size}", extra + ["--tile-size", str(size)],
                       a.runs)
        others = [(t, best(a.glint, scene, t, raw, name, extra, a.runs)) for t in measure[1:]]
        lines.append(row(label, one, cut, p, others))
    lines += ["", f"serial: the 1-thread render's time outside its phases of tiles and loops over"
              f" pixels, counted whole; loops: the first writes of its buffers and the loops over"
              f" its pixels between phases (choices, tile costs, statistics, the resolved frame),"
              f" counted at 1/{p}; at {p}: their shares of the projected seconds, as is the idle"
              f" (the phases' ends waiting on their last tiles). Loops not scaling: the efficiency"
              f" with the loops counted whole. Measured idle: the threads' time in a phase not"
              f" spent on its tiles."]
    text = "\n".join(lines) + "\n"
    with open(os.path.join(a.out, "projection.md"), "w") as f:
        f.write(text)
    print(text, end="")
    return 0


if __name__ == "__main__":
    sys.exit(main())

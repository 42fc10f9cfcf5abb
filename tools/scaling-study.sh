#!/usr/bin/env bash
# How tile rendering and the farm's tasks scale with cores (docs/performance.md, "Scaling with
# cores"). Meant for a machine with many cores; on 2 it runs, but measures little.
#
#   tools/scaling-study.sh OUTDIR [--glint PATH] [--threads "1 2 4 8 16"] [--runs R]
#                          [--scenes "default soft_shadows ..."] [--farm-scene NAME]
#                          [--farm-tiles "16 64"] [--adaptive SCENE "RENDER OPTIONS"]
#
# 1. Threads: each scene rendered R times at each thread count; the best render seconds
#    (--stats-json "seconds": no start-up), the speed-up and the parallel efficiency against one
#    thread, and from that render's "schedule" where the time went: its tiles' CPU seconds against
#    one thread's cut into the same tiles (rendered once more where more threads take smaller
#    tiles), the threads' idle in the phases and the share outside the tiles. Every count's image
#    must equal the 1-thread image (glint compare: max_abs 0), or the study stops with status 1:
#    the scheduler promises the same bytes for any thread count.
#    One more row set renders an adaptive frame (default: soft_shadows, --target-rmse 0.002
#    --max-spp 256), whose later passes are short: they sample few pixels.
#    The machine's ceiling: per scene, in each of R rounds, one 1-thread render alone and then
#    as many as the most threads at once, each process its own (nothing shared but the machine);
#    the median alone over the median of the rounds' means is the efficiency the machine itself
#    gives that many copies of the work (whatever slows the machine under load: clock speed,
#    shared caches and memory, a host's other guests). Glint's efficiency over it is what the
#    renderer itself loses.
# 2. Tiles: at the most threads, --tile-size 8/16/32/64 and --tile-order row against the default
#    (32, morton). The scheduler halves a tile until each thread has kTilesPerThread (32), so a
#    large size may run as a smaller one.
# 3. Farm: `glint-farm plan` cuts the farm scene into T tiles, one task each; the tasks run P at a
#    time with C threads each (P x C = the most threads; xargs -P does what one node of a farm
#    does, without the scheduler, whose own seconds docs/farm.md measures), then
#    `glint-farm merge` joins and checks the frame. Wall time from the first task to the merged
#    frame, best of R, against the local render at the most threads.
#
# Writes OUTDIR/scaling.md (also printed) and the renders, stats and job directories under
# OUTDIR/raw (a run replaces what an earlier one left there). Exit status: 0 done, 1 an image
# differed, 2 bad usage, another a command failed (its own status).
set -euo pipefail
shopt -s inherit_errexit # a failed render inside $(...) stops the study
export LC_ALL=C          # EPOCHREALTIME and awk with a decimal point

usage_error() {
  echo "scaling-study: $*" >&2
  exit 2
}

kRoot="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
out="" glint="${GLINT:-$kRoot/build/bin/glint}" runs=3 farm_scene=soft_shadows
threads="1 2 4 8 16" scenes="default soft_shadows depth_of_field real_assets lamp_in_mirror"
farm_tiles="16 64" adaptive_scene=soft_shadows adaptive_args="--target-rmse 0.002 --max-spp 256"
while [ $# -gt 0 ]; do
  case "$1" in
  --glint) glint=${2:?}; shift 2 ;;
  --threads) threads=${2:?}; shift 2 ;;
  --runs) runs=${2:?}; shift 2 ;;
  --scenes) scenes=${2:?}; shift 2 ;;
  --farm-scene) farm_scene=${2:?}; shift 2 ;;
  --farm-tiles) farm_tiles=${2:?}; shift 2 ;;
  --adaptive) adaptive_scene=${2:?}; adaptive_args=${3:?}; shift 3 ;;
  -*) usage_error "unknown option $1" ;;
  *) [ -z "$out" ] || usage_error "one output directory only"; out=$1; shift ;;
  esac
done
[ -n "$out" ] || usage_error "give an output directory"
[ -x "$glint" ] || usage_error "no glint binary at $glint (build it, or pass --glint PATH)"
[[ "$runs" =~ ^[1-9][0-9]*$ ]] || usage_error "--runs must be a positive integer"
for t in $threads; do [[ "$t" =~ ^[1-9][0-9]*$ ]] || usage_error "bad thread count $t"; done
most=$(echo "$threads" | tr ' ' '\n' | sort -n | tail -n 1)
raw="$out/raw"
mkdir -p "$raw"
report="$out/scaling.md"
: >"$report"

say() { echo "$*" | tee -a "$report"; }
field() { # JSON KEY → the value
  python3 -c 'import json, sys; print(json.load(open(sys.argv[1]))[sys.argv[2]])' "$1" "$2"
}
best_seconds() { # PREFIX → the least "seconds" of PREFIX.run*.json
  python3 -c 'import glob, json, sys
print(min(json.load(open(p))["seconds"] for p in glob.glob(sys.argv[1] + ".run*.json")))' "$1"
}
render_best() { # NAME SCENE ARGS... → renders R times as raw/NAME, prints the best seconds
  local name=$1 scene=$2
  shift 2
  local r
  rm -f "$raw/$name".run*.json
  for r in $(seq 1 "$runs"); do
    "$glint" render "$kRoot/scenes/$scene.json" -o "$raw/$name.exr" --quiet \
      --stats-json "$raw/$name.run$r.json" "$@"
  done
  best_seconds "$raw/$name"
}
same_image() { # A B → fails unless the pixels are equal
  "$glint" compare "$1" "$2" --json "$raw/cmp.json" >/dev/null
  [ "$(field "$raw/cmp.json" max_abs)" = 0.0 ] || {
    echo "scaling-study: $1 and $2 differ (max_abs $(field "$raw/cmp.json" max_abs))" >&2
    exit 1
  }
}
now() { echo "$EPOCHREALTIME"; }
since() { awk -v a="$1" -v b="$EPOCHREALTIME" 'BEGIN { printf "%.6f", b - a }'; } # b: read before awk starts
least() { python3 -c 'import sys; print(min(map(float, sys.argv[1:])))' "$@"; }

say "# Scaling with cores"
say ""
say "$(nproc) cores online; $(grep -m1 'model name' /proc/cpuinfo | sed 's/.*: //');" \
  "$(lscpu 2>/dev/null | grep -E '^(Thread|Core|Socket)' | tr -s ' ' | paste -sd ';')"
say "glint: $("$glint" --version | head -n 1); best of $runs runs"
say ""
say "## Threads"
say ""
say "| scene | threads | best seconds | speed-up | efficiency | Mrays/s | tile | tiles' CPU time | idle | outside the tiles |"
say "|---|---|---|---|---|---|---|---|---|---|"
# PREFIX FIRST_PREFIX CPU_PREFIX LABEL: the row of the best of PREFIX.run*.json against the best
# of FIRST_PREFIX's, then that row's efficiency on a line of its own. Each render's "schedule"
# (--stats-json) holds its tiles' thread CPU seconds and the phases' wall seconds; the tiles' CPU
# time is compared with CPU_PREFIX's, the first thread count's render cut into the same tiles.
row_of() {
  python3 - "$@" <<'PY'
import glob, json, sys
prefix, first_prefix, cpu_prefix, label = sys.argv[1:]
def best(p):
    return min((json.load(open(f)) for f in glob.glob(p + ".run*.json")), key=lambda d: d["seconds"])
def tile_cpu(d):
    return sum(t[4] for phase in d["schedule"]["phases"] for t in phase["tiles"])
d, one, same_tiles = best(prefix), best(first_prefix), best(cpu_prefix)
s, t, t1 = d["seconds"], d["schedule"]["threads"], one["schedule"]["threads"]
phases = d["schedule"]["phases"]
tiles_wall = sum(p["tiles_seconds"] for p in phases)
busy = sum(x[2] for p in phases for x in p["tiles"])
efficiency = one["seconds"] / s / t * t1
print(f"| {label} | {t} | {s:.3f} | {one['seconds'] / s:.2f} | {efficiency:.2f} | "
      f"{d['rays_total'] / s / 1e6:.0f} | {d['schedule']['tile_size']} | "
      f"{tile_cpu(d) / tile_cpu(same_tiles):.2f}x | "
      f"{100 * (1 - busy / (t * tiles_wall)):.1f} % | {100 * (1 - tiles_wall / s):.1f} % |")
print(efficiency)
PY
}
tile_size_of() { # STATS.json → the tile size the render took
  python3 -c 'import json, sys; print(json.load(open(sys.argv[1]))["schedule"]["tile_size"])' "$1"
}
thread_rows() { # LABEL NAME SCENE ARGS...: a row per thread count
  local label=$1 name=$2 scene=$3 t first="" first_size="" size cpu out
  shift 3
  for t in $threads; do
    render_best "$name.t$t" "$scene" --threads "$t" "$@" >/dev/null
    size=$(tile_size_of "$raw/$name.t$t.run1.json")
    [ -n "$first" ] || { first=$t; first_size=$size; }
    same_image "$raw/$name.t$t.exr" "$raw/$name.t$first.exr"
    cpu="$raw/$name.t$first" # more threads may take smaller tiles: compare like with like
    if [ "$size" != "$first_size" ]; then
      cpu="$raw/$name.t$first.tile$size"
      [ -e "$cpu.run1.json" ] ||
        render_best "${cpu#"$raw/"}" "$scene" --threads "$first" --tile-size "$size" "$@" >/dev/null
    fi
    out=$(row_of "$raw/$name.t$t" "$raw/$name.t$first" "$cpu" "$label")
    say "${out%$'\n'*}"
    if [ "$t" = "$most" ]; then efficiency[$name]=${out##*$'\n'}; fi
  done
}
declare -A efficiency=() # NAME → its efficiency at the most threads
rm -f "$raw"/*.t*.tile*.run*.json # an earlier study's cut renders are not this one's
for scene in $scenes; do thread_rows "$scene" "$scene" "$scene"; done
# Adaptive sampling: short later passes and the choices between them, and whether those stay
# the same for any thread count.
read -ra adaptive_words <<<"$adaptive_args"
thread_rows "$adaptive_scene, $adaptive_args" "$adaptive_scene.adaptive" "$adaptive_scene" \
  "${adaptive_words[@]}"
say ""
say "Speed-up and efficiency are against the first thread count ($(echo $threads | cut -d" " -f1)), whose"
say "image every other count's equals (glint compare, max_abs 0). Tile: the tile size the render took."
say "Tiles' CPU time: the threads' CPU seconds in the tiles against the first count's render cut into"
say "the same tiles (above 1: each tile costs more, as threads slow each other). Idle: the threads'"
say "time in the phases not spent on tiles (the phases' ends, and the gaps between tiles). Outside"
say "the tiles: the render's seconds outside its phases (set-up, loops over the pixels, the frame)."

say ""
say "## The machine's ceiling, $most processes"
say ""
say "| scene | 1 thread alone | $most at once, each | the machine's efficiency | Glint's at $most threads | Glint's over the machine's |"
say "|---|---|---|---|---|---|"
ceiling_row() { # LABEL NAME SCENE ARGS...: $most 1-thread renders at once against one alone
  local label=$1 name=$2 scene=$3 r k pid failed=0 row
  local -a pids=()
  shift 3
  rm -f "$raw/$name".alone*.json "$raw/$name".together*.json
  for r in $(seq 1 "$runs"); do # alone and together in turn: a host's load drifts over minutes
    "$glint" render "$kRoot/scenes/$scene.json" -o "$raw/$name.alone.exr" --quiet \
      --threads 1 --stats-json "$raw/$name.alone$r.json" "$@"
    pids=()
    for k in $(seq 1 "$most"); do
      "$glint" render "$kRoot/scenes/$scene.json" -o "$raw/$name.together$k.exr" --quiet \
        --threads 1 --stats-json "$raw/$name.together$r.$k.json" "$@" &
      pids+=($!)
    done
    for pid in "${pids[@]}"; do wait "$pid" || failed=$?; done # every one waited for
    [ "$failed" = 0 ] || { echo "scaling-study: a render of $scene at once failed" >&2; exit "$failed"; }
  done
  row=$(python3 - "$label" "$raw/$name" "$runs" "${efficiency[$name]}" <<'PY'
import glob, json, statistics, sys
label, prefix, runs, glint = sys.argv[1], sys.argv[2], int(sys.argv[3]), float(sys.argv[4])
seconds = lambda p: json.load(open(p))["seconds"]
alone = statistics.median(seconds(f"{prefix}.alone{r}.json") for r in range(1, runs + 1))
together = statistics.median(
    statistics.mean(seconds(p) for p in glob.glob(f"{prefix}.together{r}.*.json"))
    for r in range(1, runs + 1))
print(f"| {label} | {alone:.3f} | {together:.3f} | {alone / together:.2f} | {glint:.2f} | "
      f"{glint / (alone / together):.2f} |")
PY
  )
  say "$row"
}
for scene in $scenes; do ceiling_row "$scene" "$scene" "$scene"; done
ceiling_row "$adaptive_scene, $adaptive_args" "$adaptive_scene.adaptive" "$adaptive_scene" \
  "${adaptive_words[@]}"
say ""
say "Each of $runs rounds renders the scene alone, then $most times at once; medians over the rounds of"
say "the render alone and of the mean render seconds of the $most at once. The machine's efficiency:"
say "the render alone over that. Glint's over the machine's: what the renderer itself loses at $most"
say "threads, with what the machine loses to running $most of anything taken out."

say ""
say "## Tiles, $most threads"
say ""
say "| scene | tile 8 | 16 | 32 (default) | 64 | 32, row order |"
say "|---|---|---|---|---|---|"
for scene in $scenes; do
  row="| $scene"
  for size in 8 16 32 64; do
    seconds=$(render_best "$scene.tile$size" "$scene" --threads "$most" --tile-size "$size")
    row+=" | $(printf %.3f "$seconds")"
  done
  seconds=$(render_best "$scene.row" "$scene" --threads "$most" --tile-order row)
  row+=" | $(printf %.3f "$seconds") |"
  same_image "$raw/$scene.tile8.exr" "$raw/$scene.row.exr"
  say "$row"
done

say ""
say "## Farm tasks on one node of $most cores ($farm_scene)"
say ""
local_best=""
for r in $(seq 1 "$runs"); do
  start=$(now)
  "$glint" render "$kRoot/scenes/$farm_scene.json" -o "$raw/farm.local.exr" --quiet --threads "$most"
  local_best=$(least $local_best "$(since "$start")")
done
say "Local \`glint render\`, $most threads: $(printf %.3f "$local_best") s wall (process start to" \
  "written frame). The rows below are wall seconds from the first task's start to the merged," \
  "checked frame (process start, scene load and BVH build in every task)."
say ""
say "| tiles | tasks at a time x threads each | best wall seconds | against the local render |"
say "|---|---|---|---|"
for tiles in $farm_tiles; do
  for p in $(seq 1 "$most" | awk -v m="$most" 'm % $1 == 0 && ($1 == 1 || $1 == 4 || $1 == m)'); do
    c=$((most / p))
    best=""
    for r in $(seq 1 "$runs"); do
      job="$raw/farm.t$tiles.p$p.r$r"
      rm -rf "$job"
      GLINT="$glint" "$kRoot/tools/glint-farm" plan "$kRoot/scenes/$farm_scene.json" \
        -o "$job/frame.exr" --tiles "$tiles" --tiles-per-task 1 >>"$raw/farm.log" 2>&1
      tasks=$(awk -F '\t' 'END { print $1 + 1 }' "$job/frame.farm/tasks.tsv")
      start=$(now)
      # run-task prefers a farm's own thread count to GLINT_THREADS: not this study's.
      seq 0 $((tasks - 1)) | env -u SLURM_CPUS_PER_TASK -u CUE_THREADS GLINT_THREADS=$c xargs -P "$p" -I K \
        "$kRoot/tools/glint-farm" run-task "$job/frame.farm" K >>"$raw/farm.log" 2>&1
      "$kRoot/tools/glint-farm" merge "$job/frame.farm" >>"$raw/farm.log" 2>&1
      best=$(least $best "$(since "$start")")
      same_image "$job/frame.exr" "$raw/farm.local.exr"
    done
    row=$(python3 -c 'import sys
tiles, p, c, best, local = sys.argv[1:]
print(f"| {tiles} | {p} x {c} | {float(best):.3f} | {float(best) / float(local):.2f}x |")' \
      "$tiles" "$p" "$c" "$best" "$local_best")
    say "$row"
  done
done
say ""
say "Every merged frame equals the local render (glint compare, max_abs 0)."

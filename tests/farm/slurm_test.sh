#!/usr/bin/env bash
# Farm tests (docs/farm.md) on a real one-node Slurm cluster started here (tools/slurm-local.sh):
# munged, slurmctld and slurmd with their own key, config, ports and directories, stopped by pid
# when the test ends, whether it passes or fails.
#
#   slurm_test.sh tiles_and_animation GLINT   a 4-tile still and a 3-frame animation (2 tiles
#                                             each, then 1) through tools/glint-farm; every merged
#                                             frame equals the single-machine render byte for
#                                             byte; small tiles (frames) share a task's process
#   slurm_test.sh missing_task GLINT          one task is cancelled while it renders; the merge
#                                             names exactly that tile, and re-running that task
#                                             alone completes the frame
#   slurm_test.sh unsafe_paths GLINT          paths and options the job's scripts cannot carry
#                                             are refused before anything is written (no
#                                             cluster needed)
#
# Exit 77 (ctest: skipped) with the reason where a cluster cannot run: not root, or slurm-wlm or
# munge missing (tools/run-tests.sh installs them).
set -euo pipefail

readonly kRoot="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
readonly kCase=${1:?usage: slurm_test.sh CASE GLINT}
GLINT=$(cd "$(dirname "${2:?usage: slurm_test.sh CASE GLINT}")" && pwd)/$(basename "$2")
readonly GLINT
readonly kFarm="$kRoot/tools/glint-farm"
readonly kLocal="$kRoot/tools/slurm-local.sh"

failures=0
check() { # DESCRIPTION COMMAND...
  local what=$1
  shift
  if "$@"; then
    echo "ok: $what"
  else
    echo "FAILED: $what"
    failures=$((failures + 1))
  fi
}

# A newline in a path wrote a line of its own into render.sbatch, which sbatch ran as a
# command; a space in the job directory cut its #SBATCH --output short, and sbatch refused the
# script after the local check render. Both are refused with exit 2, nothing written.
unsafe_paths() {
  local work rc out
  work=$(mktemp -d /tmp/glint-farm-paths.XXXXXX)
  local injected=$'x\ntouch '"$work"$'/INJECTED\ny'
  mkdir -p "$work/$injected" "$work/sp ace"
  local -a plan=(plan "$kRoot/scenes/default.json" --tiles 2 --width 16 --height 16 --no-check
    --glint "$GLINT")
  rc=0
  out=$("$kFarm" "${plan[@]}" -o "$work/$injected/o.exr" 2>&1) || rc=$?
  check "a newline in the output's path is refused (exit 2)" [ "$rc" = 2 ]
  check "the refusal names the control character" grep -q "holds a control character" <<<"$out"
  rc=0
  out=$("$kFarm" "${plan[@]}" -o "$work/o.exr" --sbatch $'--mem=1G\ntouch x' 2>&1) || rc=$?
  check "a newline in an --sbatch option is refused (exit 2)" [ "$rc" = 2 ]
  rc=0
  out=$("$kFarm" "${plan[@]}" -o "$work/sp ace/o.exr" 2>&1) || rc=$?
  check "a job directory with a space is refused (exit 2)" [ "$rc" = 2 ]
  check "the refusal offers --dir" grep -q "choose one with --dir" <<<"$out"
  check "no job directory was written" [ -z "$(find "$work" -name '*.farm')" ]
  "$kFarm" "${plan[@]}" -o "$work/sp ace/o.exr" --dir "$work/job" >/dev/null 2>&1
  check "an output with a space plans with a job directory without one" \
    grep -q "^#SBATCH --output=$work/job/logs/" "$work/job/render.sbatch"
  check "nothing was injected" [ ! -e "$work/INJECTED" ]
  rm -rf "$work"
}

if [ "$kCase" = unsafe_paths ]; then
  unsafe_paths
  echo "$failures failed"
  [ "$failures" -eq 0 ]
  exit
fi

rc=0
"$kLocal" check || rc=$?
if [ "$rc" -ne 0 ]; then
  echo "SKIPPED: this machine cannot run a local Slurm cluster (reason above)"
  exit "$rc"
fi

WORK=$(mktemp -d /tmp/glint-slurm-test.XXXXXX)
cleanup() {
  local status=$?
  "$kLocal" stop "$WORK/cluster" || true
  if [ "$status" -ne 0 ]; then
    # Keep what explains the failure in the test log.
    for f in "$WORK"/cluster/log/*.log "$WORK"/*.farm/logs/*.out; do
      [ -f "$f" ] && { echo "---- $f"; tail -n 30 "$f"; }
    done
  fi
  rm -rf "$WORK"
  exit "$status"
}
trap cleanup EXIT
trap 'exit 130' INT TERM

# SHA-1 of the pixel data only (iinfo --hash): metadata such as the command line and the render
# time differ between a farm frame and a single-machine frame; the pixels must not.
pixels() { iinfo --hash "$1" | sed -n 's/^ *SHA-1: *//p'; }
same_pixels() { [ -n "$(pixels "$1")" ] && [ "$(pixels "$1")" = "$(pixels "$2")" ]; }
attribute() { iinfo -v "$1" | sed -n "s/^ *$2: *//p" | tr -d '"'; }

eval "$("$kLocal" start "$WORK/cluster")"
echo "cluster up: $SLURM_CONF"

# Small frames keep the test short; the images' content is covered by the render suite. Two
# one-CPU tasks run side by side on a two-core machine.
readonly kStill="$kRoot/scenes/whitted.json"
readonly kAnim="$kRoot/scenes/animation.json"
readonly kSize=(--width 96 --height 64)

tiles_and_animation() {
  local t0=$SECONDS
  "$kFarm" submit "$kStill" -o "$WORK/still.exr" --tiles 4 --cpus-per-task 1 --spp 4 \
    "${kSize[@]}" --glint "$GLINT" --wait
  echo "4-tile still through Slurm: $((SECONDS - t0)) s"
  "$GLINT" render "$kStill" --quiet --spp 4 "${kSize[@]}" -o "$WORK/still-ref.exr"
  check "the merged 4-tile frame equals the single-machine render byte for byte" \
    same_pixels "$WORK/still.exr" "$WORK/still-ref.exr"
  check "the merged frame records its 4 crops" [ "$(attribute "$WORK/still.exr" glint:merged_crops)" = 4 ]
  # SLURM_CPUS_PER_TASK=1 → --threads 1 in every task.
  local tile
  for tile in "$WORK"/still.farm/tiles/t00[0-3].exr; do
    check "task $(basename "$tile" .exr) rendered with the CPUs Slurm gave it (--threads 1)" \
      grep -q -- "--threads 1" <(iinfo -v "$tile")
  done
  check "no task left a partial tile behind" \
    [ -z "$(find "$WORK/still.farm/tiles" -name '*.rendering.exr')" ]
  # 48 x 32 pixels x 4 spp a tile is far below a task's 2^22 samples: the four tiles are one
  # task, rendered by one glint process (four --crop in each tile's command line).
  check "the four small tiles are one task" [ "$(cut -f 1 "$WORK/still.farm/tasks.tsv" | sort -u)" = 0 ]
  check "one glint process rendered the four tiles" \
    [ "$(attribute "$WORK/still.farm/tiles/t002.exr" glint:commandline | grep -o -- '--crop' | wc -l)" = 4 ]

  t0=$SECONDS
  "$kFarm" submit "$kAnim" -o "$WORK/anim.####.exr" --frames 1-3 --tiles 2 --cpus-per-task 1 \
    --spp 4 "${kSize[@]}" --glint "$GLINT" --wait
  echo "3-frame animation, 2 tiles each, through Slurm: $((SECONDS - t0)) s"
  local f
  for f in 1 2 3; do
    "$GLINT" render "$kAnim" --quiet --frame "$f" --spp 4 "${kSize[@]}" -o "$WORK/ref.####.exr"
    check "frame $f (anim.000$f.exr) equals the single-machine render byte for byte" \
      same_pixels "$WORK/anim.000$f.exr" "$WORK/ref.000$f.exr"
    check "frame $f records its frame number" [ "$(attribute "$WORK/anim.000$f.exr" glint:frame)" = "$f" ]
  done
  # The frames differ: the animation moves (a frozen scene would pass the checks above too).
  check "frames 1 and 3 differ" bash -c "[ '$(pixels "$WORK/anim.0001.exr")' != '$(pixels "$WORK/anim.0003.exr")' ]"
  # Six tiles in three tasks (task:frame pairs), a task never spanning two frames.
  check "the two tiles of each frame are that frame's task" \
    [ "$(cut -f 1,2 "$WORK/anim.farm/tasks.tsv" | tr '\t\n' ':,')" = "0:1,0:1,1:2,1:2,2:3,2:3," ]

  # One tile a frame: the three frames are one task, one glint process with --frames 1-3.
  "$kFarm" submit "$kAnim" -o "$WORK/whole.####.exr" --frames 1-3 --tiles 1 --cpus-per-task 1 \
    --spp 4 "${kSize[@]}" --glint "$GLINT" --wait
  check "three small frames are one task" [ "$(cut -f 1 "$WORK/whole.farm/tasks.tsv" | sort -u)" = 0 ]
  check "one glint process rendered them (--frames 1-3)" \
    grep -q -- "--frames 1-3" <(attribute "$WORK/whole.farm/tiles/f0002.t000.exr" glint:commandline)
  for f in 1 2 3; do
    check "frame $f of the grouped task equals the single-machine render byte for byte" \
      same_pixels "$WORK/whole.000$f.exr" "$WORK/ref.000$f.exr"
  done
}

missing_task() {
  # 4 tasks of 1 CPU each; at this spp a tile takes seconds, so the cancel below lands
  # while task 0 renders.
  local out
  out=$("$kFarm" submit "$kStill" -o "$WORK/frame.exr" --tiles 4 --tiles-per-task 1 \
    --cpus-per-task 1 --spp 4096 "${kSize[@]}" --glint "$GLINT")
  echo "$out"
  local job
  job=$(echo "$out" | sed -n 's/.*submitted render job \([0-9]*\).*/\1/p')
  [ -n "$job" ] || { echo "FAILED: no job id in the submit output"; return 1; }
  local i state=""
  for ((i = 0; i < 600; i++)); do
    state=$(squeue -h -j "${job}_0" -o %T 2>/dev/null || true)
    [ "$state" = RUNNING ] && break
    sleep 0.1
  done
  [ "$state" = RUNNING ] || { echo "FAILED: task 0 never ran (state '$state')"; return 1; }
  sleep 0.5 # let glint start rendering: the cancel then interrupts a real render
  scancel "${job}_0"
  echo "cancelled task 0 (job ${job}_0) while it ran"

  local merge_rc=0 report
  report=$("$kFarm" wait "$WORK/frame.farm" 2>&1) || merge_rc=$?
  echo "$report"
  check "the merge fails while a tile is missing (exit 1)" [ "$merge_rc" = 1 ]
  check "the merge names exactly the missing tile" \
    grep -q "task 0: tile 0 of 4 (--crop 0 48 0 32) is missing" <<<"$report"
  check "the merge names one missing task, no other" grep -q "1 of 4 tasks missing" <<<"$report"
  check "the merge says how to re-run it alone" \
    grep -q "glint-farm rerun $WORK/frame.farm 0\$" <<<"$report"
  check "no merged frame was written" [ ! -e "$WORK/frame.exr" ]
  check "the cancelled task left no tile" [ ! -e "$WORK/frame.farm/tiles/t000.exr" ]

  "$kFarm" rerun "$WORK/frame.farm" 0 --wait
  "$GLINT" render "$kStill" --quiet --spp 4096 "${kSize[@]}" -o "$WORK/ref.exr"
  check "after re-running task 0 alone the frame equals the single-machine render byte for byte" \
    same_pixels "$WORK/frame.exr" "$WORK/ref.exr"
}

case "$kCase" in
tiles_and_animation) tiles_and_animation ;;
missing_task) missing_task ;;
*) echo "unknown case $kCase" >&2; exit 2 ;;
esac
echo "$failures failed"
[ "$failures" -eq 0 ]

#!/usr/bin/env bash
# Renders scenes under a range of address-space limits (prlimit --as) and sorts the outcomes
# into classes: every run must end with exit 0, or exit 1 and "out of memory" (or another
# clean error), never by a signal, std::terminate or a hang (docs/hardening.md, "Memory").
#
#   tools/memory-limit-sweep.sh [-g GLINT] [-f FROM_MB] [-t TO_MB] [-s STEP_MB] SCENE...
#
# Defaults: build/bin/glint, 100 to 600 MB in steps of 20. Each run is a 32x32 frame at 1 spp
# under `timeout -s KILL 120`. Prints one line per run (limit, scene, class, first error line)
# and a summary; exits 1 when any run was a signal, a terminate or a hang.
set -uo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
glint=build/bin/glint from=100 to=600 step=20
while getopts g:f:t:s: opt; do
  case $opt in
    g) glint=$OPTARG ;;
    f) from=$OPTARG ;;
    t) to=$OPTARG ;;
    s) step=$OPTARG ;;
    *) exit 2 ;;
  esac
done
shift $((OPTIND - 1))
[ $# -gt 0 ] || { echo "usage: $0 [-g GLINT] [-f FROM_MB] [-t TO_MB] [-s STEP_MB] SCENE..." >&2; exit 2; }

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
declare -A classes
bad=0
for ((mb = from; mb <= to; mb += step)); do
  for scene in "$@"; do
    log=$work/log
    timeout -s KILL 120 prlimit --as=$((mb * 1000000)) "$glint" render "$scene" \
      -o "$work/out.exr" --width 32 --height 32 --spp 1 --quiet >"$log" 2>&1
    rc=$?
    first=$(grep -m1 -v '^$' "$log" | cut -c1-160)
    if grep -q 'terminate called' "$log"; then
      class="terminate"
    elif [ $rc -eq 137 ]; then
      class="hang (killed after 120 s)"
    elif [ $rc -gt 128 ]; then
      class="signal $(kill -l $((rc - 128)) 2>/dev/null || echo $((rc - 128)))"
    elif [ $rc -eq 0 ]; then
      class="exit 0"
    elif grep -q 'out of memory' "$log"; then
      class="exit $rc out of memory"
    else
      class="exit $rc other"
    fi
    case $class in terminate | hang* | signal*) bad=1 ;; esac
    printf '%4d MB  %-28s  %-26s  %s\n' "$mb" "$(basename "$scene")" "$class" "$first"
    classes["$class"]=$((${classes["$class"]:-0} + 1))
  done
done
echo "summary:"
for class in "${!classes[@]}"; do printf '  %-28s %d\n' "$class" "${classes[$class]}"; done
exit $bad

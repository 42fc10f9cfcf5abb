#!/usr/bin/env bash
# Makes tests/fuzz/corpus-exr/ from tiny frames rendered by Glint (GLINT=path/to/glint, default
# build/bin/glint): float and half beauty, layered and multi-part AOVs, crops, resumable frames
# (the resume state's channels), and each compression. Run once; the output is checked in.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
glint="${GLINT:-$root/build/bin/glint}"
out="$root/tests/fuzz/corpus-exr"
rm -rf "$out"
mkdir -p "$out"
scene="$(mktemp --suffix=.json)"
trap 'rm -f "$scene"' EXIT
cat >"$scene" <<'JSON'
{"render": {"width": 6, "height": 4, "spp": 1},
 "camera": {"eye": [0, 0, 4], "look_at": [0, 0, 0]},
 "materials": {"m": {"type": "phong", "kd": [0.7, 0.3, 0.2]}},
 "lights": [{"type": "point", "position": [2, 4, 3]}],
 "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "m"}]}
JSON
render() {  # render NAME ARGS...
  local name=$1
  shift
  "$glint" render "$scene" --quiet -o "$out/$name.exr" "$@"
}
render float
render half --half
render aov --aov depth,normal,albedo,objectid
render aov-half --half --aov depth,position
render multipart --multipart --aov depth,normal
render crop-left --crop 0 3 0 4
render crop-right --crop 3 6 0 4
render crop-inner --crop 1 5 1 3 --half
render resumable --resumable --spp 4 --aov variance
render resumable-crop --resumable --spp 2 --crop 2 5 1 3
for c in none rle zips piz pxr24 b44 b44a dwaa; do
  render "compression-$c" --compression "$c"
done
echo "$(ls "$out" | wc -l) seeds, $(du -sb "$out" | cut -f1) bytes in $out"

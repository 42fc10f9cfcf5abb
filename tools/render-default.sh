#!/usr/bin/env bash
# Quick start, part 1: installs what is missing, builds, and renders the bundled default scene to
# out/default.exr (scene-linear HDR) and out/default.png (for viewing).
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
glint_ensure_packages
glint_build
mkdir -p "$GLINT_ROOT/out"
"$GLINT_BUILD/bin/glint" render -o "$GLINT_ROOT/out/default.exr" \
  --display "$GLINT_ROOT/out/default.png" "$@"

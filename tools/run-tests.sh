#!/usr/bin/env bash
# Quick start, part 2: installs what is missing, builds, checks formatting, and runs the whole
# test suite under ctest. Extra arguments go to ctest (e.g. -R stress).
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
glint_ensure_packages
glint_build
"$GLINT_ROOT/tools/check-format.sh"
cd "$GLINT_BUILD"
ctest --output-on-failure -j "$(nproc)" "$@"

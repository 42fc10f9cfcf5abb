#!/usr/bin/env bash
# Quick start, part 2: installs what is missing, builds, checks formatting, and runs the whole
# test suite: ctest, then the Python module's pytest suite (tests/python). Extra arguments go to
# ctest (e.g. -R stress).
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
glint_ensure_packages
glint_build
"$GLINT_ROOT/tools/check-format.sh"
cd "$GLINT_BUILD"
status=0
ctest --output-on-failure -j "$(nproc)" "$@" || status=$?
# Debian's interpreter, which has the module's NumPy and pytest (a python3 on PATH may not).
python=/usr/bin/python3
[ -x "$python" ] || python=python3
GLINT_BUILD="$GLINT_BUILD" "$python" -m pytest -q -p no:cacheprovider "$GLINT_ROOT/tests/python" ||
  status=$?
exit "$status"

#!/usr/bin/env bash
# Fails when any C++ file differs from .clang-format; `--fix` rewrites them instead.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
# third_party/ is vendored code, kept as its authors wrote it.
mapfile -t files < <(git ls-files --cached --others --exclude-standard '*.h' '*.cpp' \
  ':!:third_party/*' 2>/dev/null || true)
[ ${#files[@]} -eq 0 ] && mapfile -t files < <(find renderer tests -name '*.h' -o -name '*.cpp')
if [ "${1:-}" = "--fix" ]; then
  clang-format -i "${files[@]}"
else
  clang-format --dry-run --Werror "${files[@]}" || {
    echo "glint: unformatted files (fix with tools/check-format.sh --fix)" >&2
    exit 1
  }
fi

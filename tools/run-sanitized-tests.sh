#!/usr/bin/env bash
# Sanitizer CI (docs/hardening.md): builds build-asan/ with clang, AddressSanitizer and
# UndefinedBehaviorSanitizer (-O1, no recovery, so any report fails its test) and runs the test
# suite there under ctest. Extra arguments go to ctest (e.g. -R stress).
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
GLINT_PACKAGES+=(clang libclang-rt-14-dev llvm-14)  # compiler, sanitizer runtimes, symbolizer
glint_ensure_packages

# Configures (every time, so the options are always these) and builds one sanitized tree.
glint_sanitized_build() {
  local dir="$1" sanitizers="$2"
  # A tree configured before Glint compiled C (MikkTSpace) has gcc as its C compiler; CMake
  # cannot switch compilers in place (it drops the -D options), so such a tree is configured afresh.
  grep -qs '^CMAKE_C_COMPILER:.*clang' "$dir/CMakeCache.txt" || rm -rf "$dir/CMakeCache.txt" "$dir/CMakeFiles"
  # Line tables, not full debug information: the reports' stacks name functions, files and lines
  # as before, and the tree builds in less time. A unity build of the renderer's libraries (the
  # tests compile file by file): each header is parsed once per eight files, not once per file;
  # the Release tree still compiles every file alone, so each one's includes stay checked.
  cmake -S "$GLINT_ROOT" -B "$dir" -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_C_COMPILER=clang \
    -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -gline-tables-only" \
    -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O1 -gline-tables-only" -DCMAKE_UNITY_BUILD=ON \
    -DGLINT_SANITIZE="$sanitizers" -DGLINT_PYTHON=OFF >/dev/null  # pytest runs in run-tests.sh only
  GLINT_BUILD="$dir" glint_build
}

export ASAN_SYMBOLIZER_PATH=/usr/lib/llvm-14/bin/llvm-symbolizer
# intercept_tls_get_addr=0: clang 14's runtime misreads glibc 2.36's dynamic TLS vectors, and
# LeakSanitizer's tracer then crashes at exit on a bogus block ("DTLS 38 at 0x4174-0x900005276",
# "Tracer caught signal 11"), after the test passed; with it off, blocks in dynamic TLS are
# still found through the heap that holds them (docs/hardening.md).
export ASAN_OPTIONS=strict_string_checks=1:detect_stack_use_after_return=1:check_initialization_order=1:intercept_tls_get_addr=0
export UBSAN_OPTIONS=print_stacktrace=1
# Leaks inside Debian's uninstrumented Assimp and OpenImageIO are not Glint's (the file says which).
export LSAN_OPTIONS="suppressions=$GLINT_ROOT/tests/fuzz/lsan.supp:print_suppressions=0"

start=$SECONDS
glint_sanitized_build "$GLINT_ROOT/build-asan" address,undefined
echo "glint: ASan+UBSan build took $((SECONDS - start)) s" >&2
start=$SECONDS
log="$GLINT_ROOT/build-asan/ctest-output.log"
status=0  # ctest's (pipefail: tee does not hide it)
# Not the farm tests: they drive a Slurm cluster through the commands the other tests run
# under ASan, and take over two minutes here, most of it the cluster's scheduling; the Release
# suite runs them.
(cd "$GLINT_ROOT/build-asan" && ctest --output-on-failure -j "$(nproc)" -LE '^farm$' "$@") 2>&1 |
  tee "$log" ||
  status=$?
echo "glint: ASan+UBSan tests took $((SECONDS - start)) s" >&2
exit "$status"

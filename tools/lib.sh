# Shared by tools/render-default.sh and tools/run-tests.sh: installs missing Debian packages,
# configures a Release build when there is none, and builds incrementally.
# shellcheck shell=bash
set -euo pipefail

GLINT_ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
GLINT_BUILD="${GLINT_BUILD:-$GLINT_ROOT/build}"

# Every Debian 12 package the build, the tests and the tools need (third_party_notes.md).
GLINT_PACKAGES=(
  build-essential cmake clang-format python3 # python3: tools/check-layers.py, run by ctest
  libembree-dev libtbb-dev libopenimageio-dev openimageio-tools libopenexr-dev libimath-dev
  libpng-dev libjpeg-dev zlib1g-dev
  libopencolorio-dev opencolorio-tools nlohmann-json3-dev libcli11-dev libassimp-dev
  libgtest-dev libbenchmark-dev
  assimp-testmodels # Assimp's real and deliberately broken models (tests/app/assimp_models_test.cpp)
  # The Python module (python/, docs/python.md), its tests and its example, for /usr/bin/python3.
  pybind11-dev python3-pybind11 python3-dev python3-pytest python3-numpy python3-matplotlib
  slurm-wlm munge # the farm tests run a one-node Slurm cluster (docs/farm.md)
)

glint_ensure_packages() {
  local missing=()
  for p in "${GLINT_PACKAGES[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  [ ${#missing[@]} -eq 0 ] && return 0
  local cmd="apt-get install -y --no-install-recommends ${missing[*]}"
  if [ "$(id -u)" -ne 0 ]; then
    echo "glint: missing Debian packages. Run as root:" >&2
    echo "  apt-get update && $cmd" >&2
    exit 1
  fi
  echo "glint: installing ${missing[*]}" >&2
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  $cmd -qq >&2
}

glint_build() {
  if [ ! -f "$GLINT_BUILD/CMakeCache.txt" ]; then
    cmake -S "$GLINT_ROOT" -B "$GLINT_BUILD" -DCMAKE_BUILD_TYPE=Release >&2
  fi
  cmake --build "$GLINT_BUILD" -j "$(nproc)" >&2
}

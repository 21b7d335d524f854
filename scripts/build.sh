#!/usr/bin/env bash
# Configures and builds one CMake preset (default: release), all its targets or only those named.
# Usage: scripts/build.sh [PRESET [TARGET...]]   (e.g. scripts/build.sh release deformcd)
set -euo pipefail
cd "$(dirname "$0")/.."
preset="${1:-release}"
targets=("${@:2}")
jobs="${DEFORMCD_JOBS:-$(nproc)}"
if command -v ccache >/dev/null 2>&1; then
  # Paths relative to the checkout, so that another clone (CI) hits the same cache entries.
  export CCACHE_BASEDIR="$PWD"
  export CCACHE_NOHASHDIR=1  # debug builds too: do not key the cache on the checkout path
  launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
else
  launcher=()
fi
cmake --preset "$preset" "${launcher[@]}" >/dev/null
if ((${#targets[@]} > 0)); then
  cmake --build --preset "$preset" -j "$jobs" --target "${targets[@]}"
else
  cmake --build --preset "$preset" -j "$jobs"
fi

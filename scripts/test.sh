#!/usr/bin/env bash
# Installs what is missing, builds a preset (default: release) and runs its tests with CTest.
# Usage: scripts/test.sh [PRESET]   (presets: release, debug, asan, nogl; asan and nogl leave out
# the tests labelled `long`, see tests/CMakeLists.txt)
# DEFORMCD_CTEST_COSTS=DIR (set by .ci/run) keeps CTest's timings of each preset's last run in
# DIR/PRESET.txt across fresh clones: with them `ctest -j` starts the longest tests first, and
# the tests that failed last time before the others.
set -euo pipefail
cd "$(dirname "$0")/.."
preset="${1:-release}"
scripts/install_deps.sh
scripts/build.sh "$preset"
timings="build/$preset/Testing/Temporary/CTestCostData.txt"
kept=""
if [[ -n "${DEFORMCD_CTEST_COSTS:-}" ]]; then
  kept="$DEFORMCD_CTEST_COSTS/$preset.txt"
  if [[ -f "$kept" && ! -f "$timings" ]]; then
    mkdir -p "$(dirname "$timings")"
    cp "$kept" "$timings"
  fi
fi
status=0
ctest --preset "$preset" -j "$(nproc)" || status=$?
if [[ -n "$kept" && -f "$timings" ]]; then
  mkdir -p "$DEFORMCD_CTEST_COSTS"
  cp "$timings" "$kept"
fi
exit "$status"

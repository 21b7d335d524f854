#!/usr/bin/env bash
# Installs what is missing, builds a preset (default: release) and runs every test with CTest.
# Usage: scripts/test.sh [PRESET]   (presets: release, debug, asan, nogl)
set -euo pipefail
cd "$(dirname "$0")/.."
preset="${1:-release}"
scripts/install_deps.sh
scripts/build.sh "$preset"
ctest --preset "$preset" -j "$(nproc)"

#!/usr/bin/env bash
# The main job: installs what is missing, builds (release), and runs deformcd on the shipped
# default: the four paper models' statistics and the OpenGL device.
# (The simulation and the paper's experiment replace this as they land.)
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install_deps.sh
scripts/build.sh release
bin=build/release/apps/deformcd/deformcd

echo
echo "== OpenGL device =="
"$bin" info --gpu || echo "(no OpenGL 4.3 here: the CPU backend remains available)"
for model in armadillo bunny dragon lion; do
  echo
  echo "== assets/models/$model =="
  "$bin" info "assets/models/$model"
done

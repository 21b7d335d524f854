#!/usr/bin/env bash
# The main job: installs what is missing, builds (release), and runs deformcd on the shipped
# default: the OpenGL device, the four paper models' statistics, and the default scene
# (scenes/phase1.json, the paper's phase 1) simulated on the GL and on the CPU backend.
# (The paper's whole experiment replaces the last step once collision detection lands.)
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
for backend in gl cpu; do
  echo
  echo "== scenes/phase1.json on $backend =="
  "$bin" run scenes/phase1.json --backend "$backend" ||
    echo "(backend $backend unavailable here)"
done

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
# The paper's phase 1 with its octree broad phase, replayed in 90 frames (the bodies move
# 5x faster than in the scene's 450): on llvmpipe the faithful octree pass takes ~2 s a frame.
for backend in gl cpu; do
  echo
  echo "== scenes/phase1.json on $backend, octree, 90 frames =="
  "$bin" run scenes/phase1.json --backend "$backend" --frames 90 --broadphase octree \
    --contacts "build/phase1_contacts_$backend.jsonl" ||
    echo "(backend $backend unavailable here)"
done

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
# The paper's experiment on phase 1 (armadillo + lion passing through each other): every method
# over the same frames, the V1 / V2 / I table, a chart, and images before, in and after contact.
# On the CPU the whole trajectory in 150 frames; on GL (llvmpipe here, a CPU rasterizer: about
# 3 s a frame for the paper's two methods) in 24.
out=build/experiment
mkdir -p "$out"
echo
echo "== the paper's experiment, phase 1, CPU backend, 150 frames =="
"$bin" bench scenes/phase1.json --backend cpu --frames 150 \
  --methods brute,octree,octree-compact,bvh \
  --json "$out/bench_cpu.json" --csv "$out/bench_cpu.csv" --plot "$out/bench_cpu.png"
echo
echo "== the paper's experiment, phase 1, GL backend, 24 frames =="
if "$bin" info --gpu >/dev/null 2>&1; then
  "$bin" bench scenes/phase1.json --backend gl --frames 24 \
    --methods brute,octree,octree-compact,bvh \
    --json "$out/bench_gl.json" --csv "$out/bench_gl.csv" --plot "$out/bench_gl.png"
  echo
  echo "== images of phase 1 (wireframe, colliding faces red and blue) =="
  "$bin" render scenes/phase1.json --frames 150 --at 30,75,120 --size 960x540 --broadphase bvh \
    --out "$out/images"
else
  echo "(no OpenGL 4.3 here: GL bench and images skipped; the CPU results above stand)"
fi
echo
echo "results in $out: bench_*.json, bench_*.csv, bench_*.png (charts), images/"

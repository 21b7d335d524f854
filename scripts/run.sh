#!/usr/bin/env bash
# The main job: installs what is missing, builds what it runs (the library and the command-line
# tool, release; scripts/test.sh builds and runs the tests), and runs deformcd on the shipped
# default: the OpenGL device, the four paper models' statistics, and the paper's experiment on
# phase 1 (scenes/phase1.json: armadillo and lion passing through each other), every collision
# method over the same frames, with the V1 / V2 / I table, a chart and images.
#
# Where the experiment runs follows the library's own rule for the backend `auto` (a hardware
# GL device: GL; a software renderer such as llvmpipe, or no OpenGL 4.3: the CPU), as
# `deformcd info --gpu --json` reports it:
#   - hardware GL: the CPU experiment, then the paper's methods on GL, then images;
#   - software renderer: the CPU experiment in full; on GL only what finishes in about a minute
#     (the BVH over the same 150 frames, about 0.2 s a frame on llvmpipe on 2 cores, and the
#     images of a 24-frame run), since the paper's brute force and octree take seconds a frame
#     there (measured 2026-12-03: octree-compact 5 s a frame in contact);
#   - no OpenGL 4.3: the CPU experiment only.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install_deps.sh
scripts/build.sh release deformcd
bin=build/release/apps/deformcd/deformcd

echo
echo "== OpenGL device =="
auto_backend=cpu
if device=$("$bin" info --gpu --json); then
  "$bin" info --gpu
  auto_backend=$(python3 -c 'import json, sys; print(json.load(sys.stdin)["auto_backend"])' \
    <<<"$device")
  gl=yes
else
  echo "(no OpenGL 4.3 here: the CPU backend remains available)"
  gl=no
fi
for model in armadillo bunny dragon lion; do
  echo
  echo "== assets/models/$model =="
  "$bin" info "assets/models/$model"
done

# The paper's experiment on phase 1: on the CPU the whole trajectory in 150 frames.
out=build/experiment
mkdir -p "$out"
methods=brute,octree,octree-compact,bvh
echo
echo "== the paper's experiment, phase 1, CPU backend, 150 frames =="
"$bin" bench scenes/phase1.json --backend cpu --frames 150 --methods "$methods" \
  --json "$out/bench_cpu.json" --csv "$out/bench_cpu.csv" --plot "$out/bench_cpu.png"

if [[ "$gl" == no ]]; then
  echo
  echo "(no OpenGL 4.3 here: GL bench and images skipped; the CPU results above stand)"
elif [[ "$auto_backend" == gl ]]; then
  echo
  echo "== the paper's experiment, phase 1, GL backend, 150 frames =="
  "$bin" bench scenes/phase1.json --backend gl --frames 150 --methods "$methods" \
    --json "$out/bench_gl.json" --csv "$out/bench_gl.csv" --plot "$out/bench_gl.png"
  echo
  echo "== images of phase 1 (wireframe, colliding faces red and blue) =="
  "$bin" render scenes/phase1.json --frames 150 --at 30,75,120 --size 960x540 --broadphase bvh \
    --out "$out/images"
else
  echo
  echo "== phase 1 on GL, the BVH only, 150 frames =="
  echo "(the OpenGL device is a software renderer, slower than the CPU backend: on it this job"
  echo " runs only what finishes in about a minute, the BVH; the paper's brute force and octree"
  echo " take seconds a frame there. On a hardware GPU it runs every method on GL.)"
  "$bin" bench scenes/phase1.json --backend gl --frames 150 --methods bvh \
    --json "$out/bench_gl.json" --csv "$out/bench_gl.csv"
  echo
  echo "== images of phase 1 in 24 frames (wireframe, colliding faces red and blue) =="
  "$bin" render scenes/phase1.json --frames 24 --at 5,12,19 --size 960x540 --broadphase bvh \
    --out "$out/images"
fi
echo
echo "results in $out: bench_*.json, bench_*.csv, bench_*.png (charts), images/"

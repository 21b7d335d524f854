#!/usr/bin/env bash
# The scaling benchmark: how collision cost grows with the surface-face count, phase 1 (armadillo
# against lion) at about 5k, 20k and 100k faces per body, and deformcd against FCL and CGAL at
# about 50k (docs/benchmarks.md, "Scaling").
#
#   scripts/scaling.sh                 generate missing fine models, build, run everything
# Options: --build-dir DIR (default build/h-scale: Release, benchmarks on), --out DIR (default
#          build/scaling), --frames N (default 24: the trajectory in N frames, 7 in contact),
#          --no-build, --skip-gl, --skip-peers, --skip-brute (no cpu_agreement).
#
# Writes to the output directory (each run's table as .txt, its numbers as .json):
#   cpu_growth     octree-compact and bvh at 5k, 20k and 100k in one run (8 min here)
#   cpu_bvh        bvh alone, median of 3 runs (5 min)
#   cpu_agreement  brute, octree, octree-compact, bvh at 5k and 20k: bench exits 1 if contacts
#                  differ; brute's cost per face-pair test (8 min)
#   gl_bvh         bvh on GL at 5k, 20k and 100k (5 min on llvmpipe)
#   peers          bench_peers, phase 1 at 5k and 50k faces per body (1 min)
#   summary.md     the tables of docs/benchmarks.md, "Scaling"
# Every run uses both cores: leave the machine otherwise idle.
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build_dir="$root/build/h-scale"
out_dir="$root/build/scaling"
frames=24
build=1
gl=1
peers=1
brute=1

die() { echo "scaling.sh: $*" >&2; exit 1; }

while (($# > 0)); do
  case "$1" in
    --build-dir) build_dir=$(realpath -m "$2"); shift 2 ;;
    --out) out_dir=$(realpath -m "$2"); shift 2 ;;
    --frames) frames="$2"; shift 2 ;;
    --no-build) build=0; shift ;;
    --skip-gl) gl=0; shift ;;
    --skip-peers) peers=0; shift ;;
    --skip-brute) brute=0; shift ;;
    -h|--help) sed -n '2,20p' "${BASH_SOURCE[0]}"; exit 0 ;;
    *) die "unknown argument '$1' (see --help)" ;;
  esac
done

scenes="$root/scenes/scaling"
fine="$root/assets/models/fine"

# --- models: only the phase-1 pair is needed here ------------------------------------------------
missing=0
for size in 20k 50k 100k; do
  for name in armadillo lion; do
    [[ -f "$fine/${name}_$size.node" ]] || missing=1
  done
done
if ((missing)); then
  echo "== generating the fine models (scripts/make_models.sh --fine --models armadillo,lion)"
  "$root/scripts/make_models.sh" --fine --models armadillo,lion
fi

# --- build ---------------------------------------------------------------------------------------
if ((build)); then
  cmake -S "$root" -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=Release -DDEFORMCD_BUILD_BENCH=ON \
    >/dev/null
  cmake --build "$build_dir" -j2 --target deformcd bench_peers >/dev/null
fi
deformcd="$build_dir/apps/deformcd/deformcd"
[[ -x "$deformcd" ]] || die "no deformcd in $build_dir"
mkdir -p "$out_dir"

bench() {  # bench NAME ARGS...: one `deformcd bench` run into NAME.json and NAME.txt (its table)
  local out=$1
  shift
  echo "== deformcd bench $*"
  "$deformcd" bench "$@" --json "$out_dir/$out.json" | tee "$out_dir/$out.txt"
}

# --- measurements --------------------------------------------------------------------------------
# Growth: every size in one run, so the ratios share the machine's state.
# scenes/phase1.json (the shipped scene, stiffer material) shows the material does not matter.
bench cpu_growth "$scenes/phase1_5k.json" "$root/scenes/phase1.json" "$scenes/phase1_20k.json" \
  "$scenes/phase1_100k.json" --backend cpu --methods octree-compact,bvh --frames "$frames"
# bvh alone, the median of 3 runs: its few milliseconds per frame are the noisiest number here.
bench cpu_bvh "$scenes/phase1_5k.json" "$root/scenes/phase1.json" "$scenes/phase1_20k.json" \
  "$scenes/phase1_100k.json" --backend cpu --methods bvh --repeat 3 --frames "$frames"
# Agreement (bench exits 1 when a method's contacts differ from brute's on any frame) and brute's
# cost per face-pair test; brute at 100k (1e10 tests a frame) is estimated from it, not run.
if ((brute)); then
  bench cpu_agreement "$scenes/phase1_5k.json" "$scenes/phase1_20k.json" --backend cpu \
    --methods brute,octree,octree-compact,bvh --frames "$frames"
fi
if ((gl)); then
  bench gl_bvh "$scenes/phase1_5k.json" "$scenes/phase1_20k.json" "$scenes/phase1_100k.json" \
    --backend gl --methods bvh --frames "$frames"
fi
if ((peers)); then
  echo "== bench_peers (phase 1 at 5k and 50k faces per body)"
  "$build_dir/bench/bench_peers" --benchmark_filter='phase1' --benchmark_min_time=0.3 \
    --benchmark_out="$out_dir/peers.json" --benchmark_out_format=json
fi

# --- summary -------------------------------------------------------------------------------------
# jq helpers: the scene's short name, a method's collision ms per contact frame, rounding, a
# markdown row from an array, and the face pairs per frame (armadillo x lion) of each scene.
jq_lib='def size: .scene | sub(".*/"; "") | sub("[.]json$"; "");
  def cd(m): .methods[m].collision_ms_per_frame.contact;
  def r: (. * 100 | round) / 100;
  def row: map(tostring) | "| " + join(" | ") + " |";
  def pairs: {"phase1_5k": (3724 * 5156), "phase1": (3724 * 5156), "phase1_20k": 4e8,
              "phase1_50k": 2.5e9, "phase1_100k": 1e10}[size];'

summary() {
  local growth="$out_dir/cpu_growth.json" agreement="$out_dir/cpu_agreement.json"
  echo "## Collision ms per contact frame, CPU, $(jq -r '.scenes[0].frames' "$growth") frames"
  echo
  echo "| scene | contact frames | bvh | bvh growth | octree-compact | growth | pairs | agree |"
  echo "|---|---|---|---|---|---|---|---|"
  jq -r "$jq_lib"'(.scenes[] | select(size == "phase1_5k")) as $base | .scenes[]
    | [size, .methods.bvh.frames_per_stage.contact, (cd("bvh") | r),
       "\(cd("bvh") / ($base | cd("bvh")) | r)x", (cd("octree-compact") | r),
       "\(cd("octree-compact") / ($base | cd("octree-compact")) | r)x", .methods.bvh.pairs,
       .methods_agree] | row' "$growth"
  if [[ -f "$out_dir/cpu_bvh.json" ]]; then
    echo
    echo "## bvh alone, CPU, median of 3 runs: collision ms per frame"
    echo
    echo "| scene | before | contact | after | contact growth | pairs |"
    echo "|---|---|---|---|---|---|"
    jq -r "$jq_lib"'(.scenes[] | select(size == "phase1_5k")) as $base | .scenes[]
      | .methods.bvh.collision_ms_per_frame as $t
      | [size, ($t.before | r), ($t.contact | r), ($t.after | r),
         "\(cd("bvh") / ($base | cd("bvh")) | r)x", .methods.bvh.pairs] | row' \
      "$out_dir/cpu_bvh.json"
  fi
  if [[ -f "$agreement" ]]; then
    echo
    echo "## Every method, CPU: collision ms per contact frame, brute's cost per face-pair test"
    echo
    echo "| scene | brute | octree | octree-compact | bvh | brute ns / test | pairs | agree |"
    echo "|---|---|---|---|---|---|---|---|"
    jq -r "$jq_lib"'.scenes[] | [size, (cd("brute") | r), (cd("octree") | r),
       (cd("octree-compact") | r), (cd("bvh") | r), (cd("brute") * 1e6 / pairs | r),
       .methods.brute.pairs, .methods_agree] | row' "$agreement"
    echo
    jq -r "$jq_lib"'.scenes[] | select(size == "phase1_20k")
      | "brute at 100k, estimated from its cost per test at 20k (not run): "
        + "\(cd("brute") / pairs * 1e10 | round) ms per contact frame"' "$agreement"
  fi
  if [[ -f "$out_dir/gl_bvh.json" ]]; then
    echo
    echo "## bvh on GL ($(jq -r '.scenes[0].device' "$out_dir/gl_bvh.json"))"
    echo
    echo "| scene | collision ms before | contact | after | pairs |"
    echo "|---|---|---|---|---|"
    jq -r "$jq_lib"'.scenes[] | .methods.bvh.collision_ms_per_frame as $t
      | [size, ($t.before | r), ($t.contact | r), ($t.after | r), .methods.bvh.pairs] | row' \
      "$out_dir/gl_bvh.json"
  fi
  if [[ -f "$out_dir/peers.json" ]]; then
    echo
    echo "## deformcd against FCL and CGAL (bench_peers), ms per contact frame"
    echo
    echo "| benchmark | ms per frame | contacts over the frames | faces |"
    echo "|---|---|---|---|"
    jq -r "$jq_lib"'.benchmarks[] | [(.name | sub("/real_time$"; "")), (.per_frame * 1e3 | r),
       (.contacts | round), .faces] | row' "$out_dir/peers.json"
  fi
}

summary | tee "$out_dir/summary.md"

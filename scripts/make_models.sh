#!/usr/bin/env bash
# Regenerates assets/models/: the paper's four test models (its Table 4) as TetGen files, from
# CGAL's data set shipped by Debian's libcgal-demo / libcgal-dev.
#
#   scripts/make_models.sh                 build the tools, regenerate everything, print the table
#   scripts/make_models.sh --search NAME   grid-search TetGen settings for one model (slow; prints
#                                          the best settings, writes nothing to assets/)
#   scripts/make_models.sh --fine          the finer versions of the four models for the scaling
#                                          benchmark (NAME_20k, NAME_50k, NAME_100k: exactly
#                                          20,000 / 50,000 / 100,000 surface faces) into
#                                          assets/models/fine/ (not committed: 3-17 MB each)
# Options: --build-dir DIR (default build/tools), --out DIR (default assets/models, with --fine
#          assets/models/fine), --no-build (use the make_models and deformcd already built in the
#          build dir), --models A,B (with --fine: only these models), --sizes 20k,100k (with
#          --fine: only these sizes; any NNk).
#
# Pipeline per model: tools/make_models (CGAL) repairs the source surface, fills its holes,
# decimates it by edge collapse to exactly the paper's surface-face count and normalizes it
# (bounding box centred at the origin, largest extent 1 m); then `deformcd tetra
# --preserve-surface` (TetGen -pY) fills it with tetrahedra, with the quality / max-volume
# settings below, found once with --search. Deterministic: same inputs, same bytes.
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build_dir="$root/build/tools"
out_dir="$root/assets/models"
search_model=""
build=1
fine=0
out_given=0

# name      source file              faces policy quality max_volume  paper: nodes tets
models=(
  "armadillo armadillo.off            3724  lt     1.36    2.51e-05    2320  7867"
  "bunny     bunny00.off              2220  lt     2.19    0.000177    1369  4702"
  "dragon    ChineseDragon-10kv.off   2020  gh     1.18    0.000229    1418  5399"
  "lion      lion.off                 5156  lt     1.38    0.0003      4233  17889"
)

# --fine: sources coarser than a size are Loop-subdivided by make_models first. TetGen keeps the
# surface and only bounds the radius-edge ratio (its default 2.0), no volume bound: few interior
# nodes (about 0.18 per surface face), so simulating the 100k models stays affordable; it is the
# surface that collision detection works on.
fine_sizes="20k,50k,100k"
fine_models="armadillo,bunny,dragon,lion"
fine_quality=2.0

# Grid of --search: quality from..to by step, max volume log-spaced over [hi, lo] (plus unset).
declare -A search_grid=(
  [armadillo]="1.25 1.75 0.01 1e-4 1e-5 21"
  [bunny]="1.6 2.3 0.01 5e-4 5e-5 21"
  [dragon]="1.1 1.4 0.01 3e-4 2e-5 21"
  [lion]="1.3 1.6 0.01 3e-4 2e-5 21"
)

die() { echo "make_models.sh: $*" >&2; exit 1; }

while (($# > 0)); do
  case "$1" in
    --build-dir) build_dir=$(realpath -m "$2"); shift 2 ;;
    --out) out_dir=$(realpath -m "$2"); out_given=1; shift 2 ;;
    --search) search_model="$2"; shift 2 ;;
    --fine) fine=1; shift ;;
    --models) fine_models="$2"; shift 2 ;;
    --sizes) fine_sizes="$2"; shift 2 ;;
    --no-build) build=0; shift ;;
    -h|--help) sed -n '2,24p' "${BASH_SOURCE[0]}"; exit 0 ;;
    *) die "unknown argument '$1' (see --help)" ;;
  esac
done

tarball=""
for candidate in /usr/share/doc/libcgal-demo/data.tar.gz /usr/share/doc/libcgal-dev/data.tar.gz; do
  if [[ -f "$candidate" ]]; then tarball="$candidate"; break; fi
done
[[ -n "$tarball" ]] || die "CGAL's data set not found: apt-get install libcgal-demo"

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# --- build -------------------------------------------------------------------------------------
if ((build)); then
  cmake -S "$root" -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=Release -DDEFORMCD_BUILD_TOOLS=ON \
    -DDEFORMCD_WITH_GL=OFF -DDEFORMCD_BUILD_TESTS=OFF -DDEFORMCD_WITH_TETGEN=ON >/dev/null
  cmake --build "$build_dir" -j2 --target make_models deformcd >/dev/null
fi
make_models="$build_dir/tools/make_models/make_models"
deformcd="$build_dir/apps/deformcd/deformcd"
[[ -x "$make_models" && -x "$deformcd" ]] || die "no make_models or deformcd in $build_dir"

sources=()
for entry in "${models[@]}"; do
  read -r _ source _ <<<"$entry"
  sources+=("data/meshes/$source")
done
tar -xzf "$tarball" -C "$work" "${sources[@]}"

# json_int KEY FILE: the integer value of "KEY" in deformcd info --json output.
json_int() { sed -n "s/^ *\"$1\": *\([0-9]*\).*/\1/p" "$2"; }

# deviation ACTUAL TARGET: signed percentage with one decimal.
deviation() { awk -v a="$1" -v t="$2" 'BEGIN { printf "%+.1f%%", 100 * (a - t) / t }'; }

# larger_deviation WORST ACTUAL TARGET: max(WORST, |deviation| in percent).
larger_deviation() {
  awk -v w="$1" -v a="$2" -v t="$3" 'BEGIN { d = 100 * (a - t) / t; if (d < 0) d = -d; print (d > w ? d : w) }'
}

model_entry() {
  for entry in "${models[@]}"; do
    read -r name _ <<<"$entry"
    if [[ "$name" == "$1" ]]; then echo "$entry"; return; fi
  done
  die "unknown model '$1' (armadillo, bunny, dragon or lion)"
}

# --- search mode ---------------------------------------------------------------------------------
# For every (quality, max volume) on the grid: tetrahedralize, count, and score by the larger of
# the node and tetrahedron deviations. Prints the ten best settings.
search() {
  local name=$1 source faces policy target_nodes target_tets
  read -r name source faces policy _ _ target_nodes target_tets <<<"$(model_entry "$name")"
  local q_from q_to q_step v_hi v_lo v_count
  read -r q_from q_to q_step v_hi v_lo v_count <<<"${search_grid[$name]}"
  "$make_models" "$work/data/meshes/$source" -o "$work/$name.off" --faces "$faces" \
    --policy "$policy" >&2
  local volumes qualities
  volumes="none $(awk -v hi="$v_hi" -v lo="$v_lo" -v n="$v_count" \
    'BEGIN { for (i = 0; i < n; ++i) printf "%.3g ", hi * (lo / hi) ^ (i / (n - 1)) }')"
  qualities=$(awk -v a="$q_from" -v b="$q_to" -v s="$q_step" \
    'BEGIN { n = int((b - a) / s + 0.5); for (i = 0; i <= n; ++i) printf "%.3g ", a + i * s }')
  for q in $qualities; do
    for v in $volumes; do
      local volume_option=()
      [[ "$v" == none ]] || volume_option=(--max-volume "$v")
      if ! "$deformcd" tetra "$work/$name.off" -o "$work/$name" --preserve-surface \
        --quality "$q" "${volume_option[@]}" >/dev/null 2>&1; then
        echo "quality $q max-volume $v: TetGen failed" >&2
        continue
      fi
      "$deformcd" info "$work/$name" --json >"$work/info.json"
      awk -v q="$q" -v v="$v" -v n="$(json_int nodes "$work/info.json")" \
        -v t="$(json_int tetrahedra "$work/info.json")" -v tn="$target_nodes" -v tt="$target_tets" \
        'function abs(x) { return x < 0 ? -x : x }
         BEGIN { dn = 100 * (n - tn) / tn; dt = 100 * (t - tt) / tt
                 printf "%6.2f  quality %-5s max-volume %-9s nodes %5d (%+.2f%%) tetrahedra %6d (%+.2f%%)\n",
                        (abs(dn) > abs(dt) ? abs(dn) : abs(dt)), q, v, n, dn, t, dt }'
    done
  done | sort -n -k1,1 -s | sed -n '1,10p'  # sed, unlike head, reads to the end: no SIGPIPE
}

if [[ -n "$search_model" ]]; then
  search "$search_model"
  exit 0
fi

# --- fine models (scaling benchmark) -------------------------------------------------------------
make_fine_models() {
  ((out_given)) || out_dir="$root/assets/models/fine"
  mkdir -p "$out_dir/surfaces"
  local table="| model | surface faces | nodes | tetrahedra | springs | seconds (CGAL + TetGen) |
|---|---|---|---|---|---|"
  local name size faces
  for name in ${fine_models//,/ }; do
    local source policy
    model_entry "$name" >/dev/null  # dies on an unknown name (a $(...) below would not)
    read -r name source _ policy _ <<<"$(model_entry "$name")"
    for size in ${fine_sizes//,/ }; do
      [[ "$size" =~ ^([0-9]+)k$ ]] || die "--sizes: '$size' is not NNk (e.g. 20k)"
      faces=$((BASH_REMATCH[1] * 1000))
      local surface="$out_dir/surfaces/${name}_$size.off" start=$SECONDS
      "$make_models" "$work/data/meshes/$source" -o "$surface" --faces "$faces" --policy "$policy"
      "$deformcd" tetra "$surface" -o "$out_dir/${name}_$size" --preserve-surface \
        --quality "$fine_quality"
      "$deformcd" info "$out_dir/${name}_$size" --json >"$work/info.json"
      [[ "$(json_int faces "$work/info.json")" == "$faces" ]] ||
        die "${name}_$size: $(json_int faces "$work/info.json") surface faces, expected $faces"
      table+="
| ${name}_$size | $faces | $(json_int nodes "$work/info.json") | $(json_int tetrahedra "$work/info.json") | $(json_int springs "$work/info.json") | $((SECONDS - start)) |"
    done
  done
  echo
  echo "$table"
}

if ((fine)); then
  make_fine_models
  exit 0
fi

# --- regenerate ------------------------------------------------------------------------------------
mkdir -p "$out_dir/surfaces"
table="| model | nodes (paper) | tetrahedra (paper) | surface faces (paper) | springs (paper) |
|---|---|---|---|---|"
worst=0
for entry in "${models[@]}"; do
  read -r name source faces policy quality max_volume target_nodes target_tets <<<"$entry"
  surface="$out_dir/surfaces/$name.off"
  "$make_models" "$work/data/meshes/$source" -o "$surface" --faces "$faces" --policy "$policy"
  "$deformcd" tetra "$surface" -o "$out_dir/$name" --preserve-surface --quality "$quality" \
    --max-volume "$max_volume"
  "$deformcd" info "$out_dir/$name" --json >"$work/info.json"
  nodes=$(json_int nodes "$work/info.json")
  tets=$(json_int tetrahedra "$work/info.json")
  surface_faces=$(json_int faces "$work/info.json")
  springs=$(json_int springs "$work/info.json")
  [[ "$surface_faces" == "$faces" ]] ||
    die "$name: $surface_faces surface faces after TetGen, expected exactly $faces"
  worst=$(larger_deviation "$worst" "$nodes" "$target_nodes")
  worst=$(larger_deviation "$worst" "$tets" "$target_tets")
  table+="
| $name | $nodes ($target_nodes, $(deviation "$nodes" "$target_nodes")) | $tets ($target_tets, $(deviation "$tets" "$target_tets")) | $surface_faces ($faces) | $springs ($((6 * target_tets))) |"
done

echo
echo "$table"
echo
echo "largest node/tetrahedron deviation from Table 4: $(printf '%.1f' "$worst")%"
awk -v w="$worst" 'BEGIN { exit !(w <= 10) }' || die "a count is more than 10% off Table 4"

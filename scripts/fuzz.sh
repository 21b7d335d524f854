#!/usr/bin/env bash
# Builds the readers' fuzz targets (preset fuzz: clang, libFuzzer, ASan + UBSan, no GL) and runs
# each for SECONDS (default 60), DEFORMCD_FUZZ_JOBS targets at a time (default 2), at nice 10.
# Usage: scripts/fuzz.sh [SECONDS] [TARGET...]   (targets: off obj stl ply tetgen scene detector)
# New inputs go to build/fuzz/corpus/TARGET (the committed seeds in fuzz/corpus/TARGET are only
# read); a finding (crash, sanitizer report, leak, hang over 10 s, a single allocation over
# 64 MB) stops that target, is saved as build/fuzz/artifacts/TARGET-*, and fails the script.
# Reproduce one with: build/fuzz/fuzz/fuzz_TARGET build/fuzz/artifacts/TARGET-crash-...
# Extra libFuzzer flags: DEFORMCD_FUZZ_ARGS="-use_value_profile=1".
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-60}"
shift || true
targets=("$@")
if ((${#targets[@]} == 0)); then targets=(off obj stl ply tetgen scene detector); fi
jobs="${DEFORMCD_FUZZ_JOBS:-2}"

nice -n 10 scripts/build.sh fuzz
out=build/fuzz
mkdir -p "$out/artifacts" "$out/logs"

run_target() {
  local t="$1"
  mkdir -p "$out/corpus/$t"
  # shellcheck disable=SC2086  # DEFORMCD_FUZZ_ARGS is a list of flags
  nice -n 10 "$out/fuzz/fuzz_$t" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
    -malloc_limit_mb=64 -print_final_stats=1 -dict="fuzz/dict/$t.dict" \
    -artifact_prefix="$out/artifacts/$t-" ${DEFORMCD_FUZZ_ARGS:-} \
    "$out/corpus/$t" "fuzz/corpus/$t" >"$out/logs/$t.log" 2>&1
}

declare -A target_of=()  # pid -> target
status=0
report() {
  local t="$1" rc="$2" log="$out/logs/$1.log"
  local execs rate took
  execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log" | tail -1)
  took=$(sed -n 's/^Done [0-9]* runs in \([0-9]*\) second.*/\1/p' "$log" | tail -1)
  if ((rc == 0)); then
    printf 'fuzz %-7s ok: %s executions in %s s (%s/s), no finding\n' "$t" "${execs:-?}" \
      "${took:-$seconds}" "${rate:-?}"
  else
    printf 'fuzz %-7s FINDING (status %s): log %s\n' "$t" "$rc" "$log"
    grep -E "ERROR|FINDING|SUMMARY|Test unit written|runtime error" "$log" | head -20 || true
    status=1
  fi
}
wait_one() {
  local pid rc=0
  wait -n -p pid || rc=$?
  report "${target_of[$pid]}" "$rc"
  unset "target_of[$pid]"
}

for t in "${targets[@]}"; do
  [[ -x "$out/fuzz/fuzz_$t" ]] || { echo "fuzz: unknown target '$t'" >&2; exit 2; }
  while ((${#target_of[@]} >= jobs)); do wait_one; done
  run_target "$t" &
  target_of[$!]="$t"
done
while ((${#target_of[@]} > 0)); do wait_one; done
exit "$status"

#!/usr/bin/env bash
# Long runs (issue 16, point 4): does memory stay flat and does the simulation stay sane over many
# frames? Runs `deformcd run SCENE --frames FRAMES --backend BACKEND --contacts FILE`, samples the
# process's resident memory (/proc/PID/status) every second, and reports the RSS after warm-up
# against the RSS at the end, the contacts per frame and whether the run blew up.
#
#   scripts/soak.sh SCENE FRAMES [BACKEND]        BACKEND: cpu (default), gl or auto
#   scripts/soak.sh scenes/phase2.json 100000 cpu
#
# With --frames N the scene's paths are replayed over N frames, so a long run goes before, in
# and after contact once, slowly. Environment (all optional):
#   DEFORMCD          the binary (default build/release/apps/deformcd/deformcd)
#   SOAK_DIR          where everything goes (default a new /tmp/deformcd-soak.XXXXXX)
#   SOAK_BROADPHASE   --broadphase (default bvh)
#   SOAK_NICE         niceness of the run (default 10)
#   SOAK_INTERVAL     seconds between samples (default 1)
#   SOAK_WARMUP       fraction of the frames after which the RSS is the reference (default 0.5:
#                     past the middle of a path scene, when the contacts have peaked)
#   SOAK_MAX_GROWTH   largest RSS growth after warm-up that passes, in % (default 1)
#   SOAK_KEEP_CONTACTS=1 keeps contacts.jsonl (it can take gigabytes; the per-frame counts stay)
# Files in SOAK_DIR: rss.csv (elapsed_s,frame,rss_kb,hwm_kb; frame as deformcd's last progress
# line said, up to 5 s old), contacts_per_frame.csv (frame,contacts), run.out and run.log
# (deformcd's stdout and stderr), summary.txt (what is printed at the end).
# Exit status: 0 when the run completed and the RSS grew less than SOAK_MAX_GROWTH % after
# warm-up; 1 when it failed, blew up or grew more; 2 for a usage error.
set -euo pipefail

usage() {
  sed -n '2,/^set -euo/p' "$0" | sed '$d; s/^# \{0,1\}//' >&2
  exit 2
}
(($# >= 2 && $# <= 3)) || usage
scene="$1"
frames="$2"
backend="${3:-cpu}"
[[ "$frames" =~ ^[1-9][0-9]*$ ]] || usage
case "$backend" in cpu | gl | auto) ;; *) usage ;; esac
[[ -f "$scene" ]] || {
  echo "soak: no scene file '$scene'" >&2
  exit 2
}

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
bin="${DEFORMCD:-$root/build/release/apps/deformcd/deformcd}"
[[ -x "$bin" ]] || {
  echo "soak: no deformcd at $bin (build it, or set DEFORMCD)" >&2
  exit 2
}
dir="${SOAK_DIR:-$(mktemp -d /tmp/deformcd-soak.XXXXXX)}"
mkdir -p "$dir"
interval="${SOAK_INTERVAL:-1}"
warmup="${SOAK_WARMUP:-0.5}"
max_growth="${SOAK_MAX_GROWTH:-1}"

csv="$dir/rss.csv"
echo "elapsed_s,frame,rss_kb,hwm_kb" >"$csv"
start=$(date +%s.%N)
nice -n "${SOAK_NICE:-10}" "$bin" run "$scene" --frames "$frames" --backend "$backend" \
  --broadphase "${SOAK_BROADPHASE:-bvh}" --contacts "$dir/contacts.jsonl" \
  >"$dir/run.out" 2>"$dir/run.log" &
pid=$!  # nice execs deformcd: the same process
trap 'kill "$pid" 2>/dev/null || true' INT TERM

# One sample: VmRSS and VmHWM in kB, and the frame of the last progress line.
while kill -0 "$pid" 2>/dev/null; do
  status=$(cat "/proc/$pid/status" 2>/dev/null) || break
  rss=$(awk '/^VmRSS:/ {print $2}' <<<"$status")
  hwm=$(awk '/^VmHWM:/ {print $2}' <<<"$status")
  frame=$(sed -n 's/^simulating: \([0-9]*\)\/.*/\1/p' "$dir/run.log" | tail -1)
  now=$(date +%s.%N)
  [[ -n "$rss" ]] && printf '%.1f,%s,%s,%s\n' "$(bc <<<"$now - $start")" "${frame:-0}" "$rss" \
    "$hwm" >>"$csv"
  sleep "$interval"
done
rc=0
wait "$pid" || rc=$?
trap - INT TERM
elapsed=$(bc <<<"$(date +%s.%N) - $start")

# Contacts per frame: one JSON line per frame, one {"a":...} per contact.
counts="$dir/contacts_per_frame.csv"
echo "frame,contacts" >"$counts"
if [[ -f "$dir/contacts.jsonl" ]]; then
  awk '{ n = gsub(/\{"a":/, ""); f = $0; sub(/^\{"frame":/, "", f); sub(/,.*/, "", f);
         print f "," n }' "$dir/contacts.jsonl" >>"$counts"
  [[ "${SOAK_KEEP_CONTACTS:-0}" == 1 ]] || rm -f "$dir/contacts.jsonl"
fi

{
  echo "scene      $scene, $frames frames, backend $backend, broad phase ${SOAK_BROADPHASE:-bvh}"
  echo "binary     $bin"
  printf 'wall time  %.0f s (%d samples)\n' "$elapsed" "$(($(wc -l <"$csv") - 1))"
  sed -n 's/^backend  *//p; s/^time  *//p' "$dir/run.out" | sed 's/^/deformcd   /'
  # RSS: the reference is the first sample at or past the warm-up frame.
  awk -F, -v frames="$frames" -v warmup="$warmup" -v max_growth="$max_growth" '
    NR == 1 { next }
    { n++; rss[n] = $3; fr[n] = $2; t[n] = $1; if ($4 > hwm) hwm = $4 }
    !ref && $2 >= warmup * frames { ref = n }
    END {
      if (n == 0) { print "rss        no samples"; exit }
      if (!ref) ref = n
      growth = 100 * (rss[n] - rss[ref]) / rss[ref]
      printf "rss        start %d kB, after warm-up (frame %d, %.0f s) %d kB, end (frame %d, %.0f s) %d kB, peak %d kB\n", rss[1], fr[ref], t[ref], rss[ref], fr[n], t[n], rss[n], hwm
      printf "growth     %+.2f %% after warm-up (limit %s %%): %s\n", growth, max_growth, (growth < max_growth ? "pass" : "FAIL")
    }' "$csv"
  awk -F, -v frames="$frames" '
    NR == 1 { next }
    { n++; total += $2; if ($2 > 0) { touching++; if (!first) first = $1 + 0; last = $1 }
      if ($2 > peak) { peak = $2; peak_frame = $1 } }
    END {
      printf "contacts   %d frames recorded of %d + 1", n, frames
      if (touching) printf "; %d in contact (frames %d-%d), %d face pairs in all, %.1f per frame in contact, at most %d (frame %d)", touching, first, last, total, total / touching, peak, peak_frame
      printf "\n"
    }' "$counts"
  if ((rc == 0)); then
    echo "blew up    no (deformcd exited 0)"
  else
    echo "blew up    deformcd exited $rc: $(grep -v '^simulating:' "$dir/run.log" | tail -2 | tr '\n' ' ')"
  fi
  echo "files      $dir"
} | tee "$dir/summary.txt"

((rc == 0)) || exit 1
grep -q '^growth .*: pass$' "$dir/summary.txt" || exit 1

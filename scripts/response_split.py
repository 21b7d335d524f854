#!/usr/bin/env python3
"""The contact response's time against the simulation's, from `perf` samples of one bench run.

Usage: scripts/response_split.py [--runs N] [--deformcd PATH] [BENCH ARGUMENT...]
  (default: build/release/apps/deformcd/deformcd, and the bench arguments
   scenes/impact.json --frames 80 --backend cpu --methods bvh --threads 1)

On a machine whose speed changes from run to run (this project's VMs: the simulation alone
took 21 to 45 ms a frame within an hour), two builds' wall-clock ratios within 15 % do not
compare. The shares of one run's samples do: whatever slows the machine slows the simulation
and the response alike. Each run prints the bench's own line and the samples of three groups
of functions (CPU backend), each over the simulation's:
  simulation  CpuSimulation's passes (tetrahedra, spring edges, nodes)
  searches    the proximity search and widenings (CpuProximity, primitive tests, the host side)
  substeps    the per-substep projections (CpuContactResponse, contact geometry, solve)
Needs `perf` (Debian: linux-perf) and a build with symbols (the release preset has them).
"""

import argparse
import os
import re
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DEFAULT_BENCH = ["scenes/impact.json", "--frames", "80", "--backend", "cpu", "--methods", "bvh",
                 "--threads", "1"]

# A symbol's group: the first pattern it matches.
GROUPS = [
    ("simulation", re.compile(r"CpuSimulation|tet_volume_forces|spring_edge_states")),
    ("substeps", re.compile(r"CpuContactResponse|contact_geometry|solve_contact|contact_clear"
                            r"|contact_active|apply_correction|SweepOrder")),
    ("searches", re.compile(r"CpuProximity|primitives_within|emit_face_pair|emit_if_within"
                            r"|add_proximity_pair|to_proximity_pairs|query_bvh|refit_bvh"
                            r"|ContactResponse::widen|ContactResponse::search|sweep_")),
]


def split(deformcd, bench_args):
    with tempfile.TemporaryDirectory() as tmp:
        data = os.path.join(tmp, "perf.data")
        bench = subprocess.run(["perf", "record", "-q", "-o", data, deformcd, "bench", *bench_args],
                               cwd=ROOT, capture_output=True, text=True)
        if bench.returncode != 0:
            sys.exit(bench.stdout + bench.stderr)
        lines = [line.strip() for line in bench.stdout.splitlines() if "x the simulation" in line]
        report = subprocess.run(["perf", "report", "-i", data, "--no-children", "--sort", "symbol",
                                 "--stdio"], capture_output=True, text=True, check=True).stdout
    shares = {name: 0.0 for name, _ in GROUPS}
    for line in report.splitlines():
        match = re.match(r"\s*([0-9.]+)%\s+\[\.\]\s+(.*)", line)
        if not match:
            continue
        for name, pattern in GROUPS:
            if pattern.search(match.group(2)):
                shares[name] += float(match.group(1))
                break
    return lines, shares


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=1)
    parser.add_argument("--deformcd", default=os.path.join(ROOT, "build/release/apps/deformcd/deformcd"))
    parser.add_argument("bench", nargs=argparse.REMAINDER)
    opts = parser.parse_args()
    bench_args = opts.bench or DEFAULT_BENCH
    for run in range(opts.runs):
        lines, shares = split(opts.deformcd, bench_args)
        simulation = shares["simulation"]
        print(f"run {run + 1}: " + " | ".join(lines))
        if simulation <= 0.0:
            sys.exit("no samples in the simulation's functions (a CPU-backend bench?)")
        print(f"  samples: simulation {simulation:.1f} %, searches {shares['searches']:.1f} % "
              f"({shares['searches'] / simulation:.3f} of the simulation's), substeps "
              f"{shares['substeps']:.1f} % ({shares['substeps'] / simulation:.3f})")


if __name__ == "__main__":
    main()

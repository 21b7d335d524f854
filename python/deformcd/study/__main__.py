"""python3 -m deformcd.study SCENE --vary KEY=V1,V2,... [--vary ...] [--scheduler ADDRESS]
[--out results.csv]: the study's command line (docs/study.md).

A Python entry point rather than a `deformcd study` subcommand: the study is Python (Dask,
pandas) through and through, and the `deformcd` tool is a C++ program that neither links
Python nor knows which interpreter and which module the user's environment has; a subcommand
would only start this one, with less say over the interpreter.
"""

import argparse
import json
import sys

import pandas

from . import parse_vary, run


def parser():
    p = argparse.ArgumentParser(
        prog="python3 -m deformcd.study",
        description="Runs every variation of a scene as a Dask task (a local cluster by "
                    "default) and writes one row per run: parameters, status, error, contacts "
                    "per frame, time per frame by stage.")
    p.add_argument("scene", help="the base scene (JSON)")
    p.add_argument("--vary", action="append", default=[], metavar="KEY=V1,V2,...",
                   help="a scene key and its values, e.g. settings.substeps=8,16 or "
                        "bodies.0.velocity=[1,0,0],[2,0,0] (JSON values; strings bare); several "
                        "--vary make a grid. Run keys: frames, broadphase, seed, perturb")
    p.add_argument("--list", metavar="FILE",
                   help="the runs as a JSON list of {key: value} objects, instead of --vary")
    p.add_argument("--frames", type=int, help="frames per run (the scene's by default)")
    p.add_argument("--broadphase", default="bvh", help="collision broad phase (default bvh)")
    p.add_argument("--backend", default="cpu", choices=("cpu", "gl", "auto"),
                   help="the worlds' backend (default cpu: the same bits on every machine)")
    p.add_argument("--threads", type=int, default=1,
                   help="CPU threads per run (default 1); the local cluster has cores/threads "
                        "workers")
    p.add_argument("--workers", type=int, help="local cluster: worker processes")
    p.add_argument("--scheduler", metavar="ADDRESS",
                   help="a running Dask scheduler, e.g. tcp://10.0.0.5:8786 (default "
                        "$DASK_SCHEDULER_ADDRESS, else a local cluster)")
    p.add_argument("--out", metavar="FILE", help="write the rows: .csv (or .parquet, with "
                                                 "pyarrow)")
    p.add_argument("--outputs", metavar="DIR",
                   help="each run's final state (run_NNNN.npz) and scene (run_NNNN.json); a "
                        "path every worker can write")
    p.add_argument("--models", choices=("ship", "shared"), default="ship",
                   help="ship the models' files with the tasks (default), or let the workers "
                        "read them at their absolute paths (a shared file system)")
    p.add_argument("--cli", help="the deformcd tool, to mesh surface models (default "
                                 "$DEFORMCD_CLI, else deformcd on PATH)")
    p.add_argument("--cache", metavar="DIR", help="meshed surface models (default "
                                                  "~/.cache/deformcd/tetra)")
    p.add_argument("--no-census", dest="census", action="store_false",
                   help="skip the intersection census each frame (its columns stay empty)")
    p.add_argument("--quiet", action="store_true", help="no progress messages")
    return p


def main(argv=None):
    args = parser().parse_args(argv)
    try:
        vary = dict(parse_vary(v) for v in args.vary) if args.vary else None
        variations = None
        if args.list:
            with open(args.list, encoding="utf-8") as f:
                variations = json.load(f)
        log = (lambda *_: None) if args.quiet else (lambda m: print(m, file=sys.stderr))
        rows = run(args.scene, vary, variations, frames=args.frames,
                   broadphase=args.broadphase, backend=args.backend, threads=args.threads,
                   workers=args.workers, scheduler=args.scheduler, out=args.out,
                   outputs=args.outputs, models=args.models, cli=args.cli,
                   cache_dir=args.cache, census=args.census, log=log)
    except (ValueError, OSError, RuntimeError) as e:
        print(f"deformcd.study: {e}", file=sys.stderr)
        return 2
    shown = [c for c in rows.columns if c not in ("contacts_per_frame", "constraints_per_frame",
                                                  "state_hash", "error", "output", "worker_pid")]
    with pandas.option_context("display.width", 160, "display.max_columns", 40):
        print(rows[shown].to_string(index=False))
    for _, row in rows[rows["status"] != "ok"].iterrows():
        print(f"run {row['run']}: {row['status']}: {row['error']}")
    return 0


if __name__ == "__main__":
    sys.exit(main())

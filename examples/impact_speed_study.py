#!/usr/bin/python3
"""A parameter study on Dask: the impact scene's armadillo thrown at the lion at several speeds,
each run a task; how often their surfaces intersect despite the contact response, and what a
frame costs, against the speed.

    PYTHONPATH=build/release/python /usr/bin/python3 examples/impact_speed_study.py out.png
    ... --speeds 0.5,1,2,4,8 --frames 100 --csv rows.csv --scheduler tcp://HOST:8786

Runs on a local cluster sized to the machine unless --scheduler (or $DASK_SCHEDULER_ADDRESS)
names one. Draws two panels into the PNG (matplotlib, Agg: no display needed): intersecting
frames per speed, and the mean time per frame by stage (simulation, collision detection, the
response's proximity search and projections). A run that blows up is marked with an x and its
error printed; the others are drawn.
"""

import argparse
import pathlib
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from deformcd import study  # noqa: E402

SCENE = pathlib.Path(__file__).resolve().parents[1] / "scenes" / "impact.json"
STAGES = ("simulation", "collision", "proximity", "response")


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("png", help="the picture to write")
    p.add_argument("--speeds", default="0.5,1,1.5,2,3,4,6",
                   help="the armadillo's speeds toward the lion, m/s (comma-separated)")
    p.add_argument("--frames", type=int, default=100)
    p.add_argument("--csv", help="also write the study's rows")
    p.add_argument("--scheduler", help="a Dask scheduler's address (default: a local cluster)")
    p.add_argument("--workers", type=int, help="local cluster: worker processes")
    args = p.parse_args(argv)
    speeds = [float(s) for s in args.speeds.split(",")]

    rows = study.run(SCENE, vary={"bodies.armadillo.velocity.0": speeds}, frames=args.frames,
                     scheduler=args.scheduler, workers=args.workers, out=args.csv)
    rows["speed"] = rows["bodies.armadillo.velocity.0"]
    print(rows[["speed", "status", "frames", "intersecting_frames", "max_contacts",
                "constraint_frames", "ms_per_frame"]].to_string(index=False))
    for _, row in rows[rows["status"] != "ok"].iterrows():
        print(f"speed {row['speed']}: {row['status']}: {row['error']}")

    ok = rows[rows["status"] == "ok"]
    failed = rows[rows["status"] != "ok"]
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(7, 7), sharex=True)
    top.plot(ok["speed"], ok["intersecting_frames"], "o-", label="intersecting frames")
    top.plot(ok["speed"], ok["constraint_frames"], "s--", label="frames with contact constraints")
    if len(failed):
        top.plot(failed["speed"], [0] * len(failed), "rx", markersize=10, label="blew up")
    top.set_ylabel(f"frames (of {args.frames})")
    top.set_title("impact.json: armadillo's speed against the contact response")
    top.legend()
    bottom_edge = [0.0] * len(ok)
    for stage in STAGES:
        ms = list(ok[f"ms_per_frame_{stage}"])
        bottom.bar(ok["speed"], ms, width=0.25, bottom=bottom_edge, label=stage)
        bottom_edge = [b + m for b, m in zip(bottom_edge, ms)]
    bottom.set_xlabel("armadillo's speed toward the lion (m/s)")
    bottom.set_ylabel("ms per frame (mean, 1 thread)")
    bottom.legend()
    fig.tight_layout()
    fig.savefig(args.png, dpi=100)
    print(f"wrote {args.png}")
    return 0


if __name__ == "__main__":
    sys.exit(main())

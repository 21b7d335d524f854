"""Parameter studies and datasets: many variations of one scene, each run as a Dask task, one
row per run in a pandas DataFrame.

    from deformcd import study
    rows = study.run("scenes/impact.json",
                     vary={"bodies.0.velocity": [[1, 0, 0], [2, 0, 0], [3, 0, 0]],
                           "settings.substeps": [8, 16]},
                     frames=100, out="impact.csv")

Each row: run (its index), the parameters, status ("ok", "blew up", "error"), error,
error_stage ("setup", "step", or a blow-up's "simulation"/"response"), error_frame, error_body,
error_body_name, frames (stepped), intersecting_frames, first_intersecting_frame,
max_contacts, contacts_per_frame (a list, frame 1 first), constraint_frames, max_constraints,
constraints_per_frame (the contact response's proximity pairs), census_frames, max_between_pairs,
max_self_pairs, max_inside_vertices (the intersection census, bodies with themselves included,
each frame; census=False leaves them None and saves its cost), ms_per_frame_<stage>
(simulation, collision, proximity, response; means) and ms_per_frame (their sum), wall_s,
state_hash (SHA-256 of the final positions and velocities: equal for equal runs, bit for bit),
output (the run's .npz with outputs=), worker_pid.

Where: a local cluster of worker processes sized to the machine by default; `scheduler=` (or
$DASK_SCHEDULER_ADDRESS) for a running cluster; `client=` for a distributed.Client of your own.
The same code runs on both. Command line: python3 -m deformcd.study (see __main__.py), and
docs/study.md for laptops, clusters and what the workers need.
"""

import json
import pathlib
import time
import uuid

from . import cluster, results, task
from . import models as _models
from . import variations as _variations
from .variations import parse_vary

__all__ = ["run", "parse_vary"]


def run(scene, vary=None, variations=None, *, frames=None, broadphase="bvh",
        backend="cpu", threads=1, workers=None, scheduler=None, client=None, out=None,
        outputs=None, models="ship", cli=None, cache_dir=None, census=True, log=print):
    """Runs every variation of `scene` and returns one row per run (a pandas DataFrame).

    scene: the base scene file (JSON). vary: {key: [values]}, the grid over them (the last key
    varying fastest); or variations: [{key: value}, ...], the runs themselves (see
    deformcd.study.variations for the keys). frames, broadphase: every run's, unless varied
    ("frames", "broadphase" keys). backend: "cpu" (bit-for-bit the same on every machine) or
    "gl"/"auto" where the workers have a GPU. threads: CPU threads per run, which sizes the local
    cluster (cores // threads workers; `workers` to choose). scheduler, client: run on a cluster
    (cluster.dask_client). out: write the rows too (.csv; .parquet needs pyarrow). outputs: a
    folder (shared by the workers) for each run's final state (run_NNNN.npz) and scene.
    models: "ship" (send the models' files with the tasks) or "shared" (the workers read
    them at their absolute paths). cli, cache_dir: the `deformcd` tool meshing surface models,
    and where their meshes are kept (models.py). census: the intersection census every frame
    (World.intersection_census; an exact pass of its own). log: progress messages (None for
    silence).
    """
    import distributed

    log = log or (lambda *_: None)
    if out is not None:
        results.output_format(out)  # before any run: a format that cannot be written fails now
    scene_file = pathlib.Path(scene)
    base = json.loads(scene_file.read_text())
    params_list = _variations.expand(vary, variations)
    preparer = _models.ModelPreparer(scene_file.resolve().parent, models, cli, cache_dir, log)
    tasks = []
    for i, params in enumerate(params_list):
        varied, run_keys = _variations.apply(base, params)
        tasks.append({
            "run": i, "params": params, "scene": preparer.prepare(varied),
            "frames": run_keys.get("frames", frames), "broadphase":
            run_keys.get("broadphase", broadphase), "backend": backend, "threads": threads,
            "outputs": str(pathlib.Path(outputs).resolve()) if outputs else None,
            "census": census,
        })
    keys = list(dict.fromkeys(k for p in params_list for k in p))
    start = time.perf_counter()
    rows = []
    with cluster.dask_client(client, scheduler, workers, threads, log) as dask:
        bundle = dask.scatter(preparer.bundle, broadcast=True) if preparer.bundle else {}
        study_id = uuid.uuid4().hex[:12]  # the tasks' keys name their run: run_variation-0003-...
        futures = {dask.submit(task.run_variation, t, bundle,
                               key=f"run_variation-{t['run']:04d}-{study_id}"): t for t in tasks}
        for future in distributed.as_completed(futures):
            t = futures[future]
            try:
                row = future.result()
            except Exception as e:  # noqa: BLE001 (the task itself never raises: a lost worker)
                row = {"run": t["run"], **t["params"], "status": "error",
                       "error": f"{type(e).__name__}: {e}", "error_stage": "worker"}
            rows.append(row)
            log(f"study: run {row['run']} {row['status']} ({len(rows)}/{len(tasks)})")
    log(f"study: {len(tasks)} runs in {time.perf_counter() - start:.1f} s")
    frame = results.to_frame(rows, keys)
    if out is not None:
        results.write(frame, out)
        log(f"study: wrote {out}")
    return frame

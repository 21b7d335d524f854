"""One run of a study, on a worker: the varied scene stepped frame by frame with deformcd.World,
measured, and summed up as one row. Whatever goes wrong becomes the row's error: a study never
loses a run to an exception (a worker that dies is Dask's to retry, see cluster.py).
"""

import hashlib
import json
import os
import pathlib
import tempfile
import time

import numpy as np

import deformcd

from .models import write_models

STAGES = ("simulation", "collision", "proximity", "response")


def state_hash(world):
    """SHA-256 of every body's positions then velocities, body by body, as the float32 arrays
    World returns (C order): equal hashes are bit-for-bit equal states."""
    digest = hashlib.sha256()
    for b in range(world.body_count):
        digest.update(np.ascontiguousarray(world.positions(b), dtype=np.float32).tobytes())
        digest.update(np.ascontiguousarray(world.velocities(b), dtype=np.float32).tobytes())
    return digest.hexdigest()


def run_variation(task, bundle):
    """task: {"run", "params", "scene" (dict), "frames", "broadphase", "backend", "threads",
    "outputs" (a folder or None), "census" (bool)}; bundle: the shipped models (models.py).
    Returns the row."""
    row = {"run": task["run"], **task["params"], "status": "ok", "error": None,
           "error_stage": None, "error_frame": None, "error_body": None, "error_body_name": None,
           "frames": 0}
    counts, constraints, times = [], [], {stage: [] for stage in STAGES}
    census = [] if task.get("census", True) else None
    world = None
    start = time.perf_counter()
    with tempfile.TemporaryDirectory(prefix="deformcd-study-") as folder:
        scene_file = pathlib.Path(folder) / "scene.json"
        stage = "setup"
        try:
            write_models(folder, bundle, task["scene"])
            scene_file.write_text(json.dumps(task["scene"]))
            world = deformcd.World.from_scene(scene_file, frames=task["frames"],
                                              backend=task["backend"],
                                              broadphase=task["broadphase"],
                                              threads=task["threads"], measure_stage_times=True)
            stage = "step"
            for _ in range(world.frames):
                world.step()
                counts.append(int(world.counts()["contacts"]))
                response = world.response_counts()
                constraints.append(int(response["vertex_face"] + response["edge_edge"]))
                for name, seconds in world.last_frame_times().items():
                    times[name[:-len("_s")]].append(seconds)
                if census is not None:
                    try:
                        census.append(world.intersection_census())
                    except deformcd.InputError:
                        # Positions beyond the detector's range: a blow-up under way, which
                        # the world's own check reports at its next step; no census of it.
                        pass
        except deformcd.SimulationError as e:
            row.update(status="blew up", error=str(e), error_stage=e.stage, error_body=e.body,
                       error_body_name=e.body_name,
                       error_frame=e.frame if e.frame is not None else len(counts) + 1)
        except Exception as e:  # noqa: BLE001 (a row, not a lost study)
            row.update(status="error", error=f"{type(e).__name__}: {e}", error_stage=stage)
            if stage == "step":
                row["error_frame"] = len(counts) + 1
        row["wall_s"] = time.perf_counter() - start
        row.update(_summary(counts, constraints, times))
        row.update(_census_summary(census))
        row["state_hash"] = state_hash(world) if world is not None else None
        row["output"] = _save(task, world, counts) if world is not None else None
    row["worker_pid"] = os.getpid()
    return row


def _summary(counts, constraints, times):
    frames = len(counts)
    contact_frames = [f + 1 for f, n in enumerate(counts) if n > 0]
    summary = {
        "frames": frames,
        "intersecting_frames": len(contact_frames),
        "first_intersecting_frame": contact_frames[0] if contact_frames else None,
        "max_contacts": max(counts) if counts else 0,
        "constraint_frames": sum(1 for n in constraints if n > 0),
        "max_constraints": max(constraints) if constraints else 0,
        "contacts_per_frame": counts,
        "constraints_per_frame": constraints,
    }
    total = 0.0
    for stage, seconds in times.items():
        mean_ms = 1e3 * sum(seconds) / len(seconds) if seconds else float("nan")
        summary[f"ms_per_frame_{stage}"] = mean_ms
        total += mean_ms
    summary["ms_per_frame"] = total
    return summary


def _census_summary(census):
    """The intersection census over the frames (World.intersection_census: pairs between bodies,
    of a body with itself, vertices inside another body), which folding cannot hide as the
    collision pass's contacts can (they leave out a body with itself without collision.self);
    None in every column when the study ran without it."""
    keys = ("between_pairs", "self_pairs", "inside_vertices")
    if census is None:
        return {"census_frames": None, **{f"max_{k}": None for k in keys}}
    return {"census_frames": sum(1 for c in census if any(c[k] for k in keys)),
            **{f"max_{k}": max((c[k] for c in census), default=0) for k in keys}}


def _save(task, world, counts):
    """With task["outputs"]: FOLDER/run_NNNN.npz (each body's final positions and velocities,
    the contacts per frame) and FOLDER/run_NNNN.json (the scene run). Returns the .npz path."""
    if not task.get("outputs"):
        return None
    folder = pathlib.Path(task["outputs"])
    folder.mkdir(parents=True, exist_ok=True)
    name = f"run_{task['run']:04d}"
    arrays = {"contacts_per_frame": np.asarray(counts, dtype=np.int64)}
    for b in range(world.body_count):
        arrays[f"positions_{b}"] = world.positions(b)
        arrays[f"velocities_{b}"] = world.velocities(b)
    np.savez(folder / (name + ".npz"), **arrays)
    (folder / (name + ".json")).write_text(json.dumps(task["scene"], indent=1))
    return str(folder / (name + ".npz"))

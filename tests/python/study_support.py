"""Shared by the study's tests (test_study_*.py): Dask (their module is skipped without it), a
cluster of separate processes on 127.0.0.1 (conftest.py's separate_cluster fixture), and the
serial reference run with deformcd.World."""

import hashlib
import json
import os
import pathlib
import subprocess
import sys
import time

import numpy as np
import pytest

pytest.importorskip("distributed", reason="python3-distributed (Dask) is not installed")
pytest.importorskip("pandas", reason="python3-pandas is not installed")

import deformcd  # noqa: E402

STARTUP_S = 60  # a loaded 2-core machine starts a Python process with Dask in a few seconds


class SeparateCluster:
    """A scheduler and workers, each its own `python3 -m distributed.cli...` process bound to
    127.0.0.1, as on a real cluster; workers without nannies, one thread each."""

    def __init__(self, folder, workers=2):
        self.folder = folder
        self.scheduler_file = folder / "scheduler.json"
        env = dict(os.environ)
        self.scheduler = self._start(
            ["distributed.cli.dask_scheduler", "--host", "127.0.0.1", "--port", "0",
             "--no-dashboard", "--scheduler-file", str(self.scheduler_file)], env, "scheduler")
        deadline = time.monotonic() + STARTUP_S
        while not self.scheduler_file.exists():
            self._check_alive(deadline)
        self.address = json.loads(self.scheduler_file.read_text())["address"]
        self.workers = [
            self._start(["distributed.cli.dask_worker", self.address, "--host", "127.0.0.1",
                         "--nthreads", "1", "--no-nanny", "--no-dashboard"], env, f"worker{i}")
            for i in range(workers)]
        import distributed

        with distributed.Client(self.address, timeout=f"{STARTUP_S}s") as client:
            client.wait_for_workers(workers, timeout=STARTUP_S)

    def _start(self, module_args, env, name):
        log = open(self.folder / f"{name}.log", "w")
        return subprocess.Popen([sys.executable, "-m", *module_args], env=env, stdout=log,
                                stderr=subprocess.STDOUT)

    def _check_alive(self, deadline):
        if self.scheduler.poll() is not None or time.monotonic() > deadline:
            raise RuntimeError("the scheduler did not start: "
                               + (self.folder / "scheduler.log").read_text())
        time.sleep(0.1)

    def stop(self):
        for process in [*self.workers, self.scheduler]:
            if process.poll() is None:
                process.terminate()
        for process in [*self.workers, self.scheduler]:
            try:
                process.wait(timeout=10)
            except subprocess.TimeoutExpired:
                process.kill()


def serial_run(scene, scene_dir, folder, frames, broadphase="bvh"):
    """The run done serially in this process with deformcd.World (every core: results do not
    depend on the thread count): the scene dict written to folder (its relative models made
    absolute against scene_dir), stepped frame by frame. Returns contacts per frame, the final
    state and its SHA-256 (positions then velocities, body by body, float32), or the blow-up."""
    scene = json.loads(json.dumps(scene))
    for body in scene["bodies"]:
        body["model"] = str((pathlib.Path(scene_dir) / body["model"]).resolve())
    path = pathlib.Path(folder) / "serial.json"
    path.write_text(json.dumps(scene))
    world = deformcd.World.from_scene(path, frames=frames, backend="cpu", broadphase=broadphase)
    result = {"contacts_per_frame": [], "census": [], "error": None}
    try:
        for _ in range(frames):
            world.step()
            result["contacts_per_frame"].append(int(world.counts()["contacts"]))
            try:
                result["census"].append(world.intersection_census())
            except deformcd.InputError:  # a blow-up under way (as the study's task.py)
                pass
    except deformcd.SimulationError as e:
        result["error"] = e
    digest = hashlib.sha256()
    result["positions"], result["velocities"] = [], []
    for b in range(world.body_count):
        p, v = world.positions(b), world.velocities(b)
        result["positions"].append(p)
        result["velocities"].append(v)
        digest.update(p.tobytes())
        digest.update(v.tobytes())
    result["state_hash"] = digest.hexdigest()
    return result


def assert_row_equals_serial(row, serial):
    """Bit for bit: contacts per frame, the final state's hash, the census's columns, and (with
    outputs) its arrays."""
    assert row["contacts_per_frame"] == serial["contacts_per_frame"], row["run"]
    census = serial["census"]
    keys = ("between_pairs", "self_pairs", "inside_vertices")
    assert row["census_frames"] == sum(1 for c in census if any(c[k] for k in keys)), row["run"]
    for k in keys:
        assert row[f"max_{k}"] == max((c[k] for c in census), default=0), (row["run"], k)
    assert row["state_hash"] == serial["state_hash"], row["run"]
    if row.get("output"):
        saved = np.load(row["output"])
        for b, (p, v) in enumerate(zip(serial["positions"], serial["velocities"])):
            assert np.array_equal(saved[f"positions_{b}"], p, equal_nan=True)
            assert np.array_equal(saved[f"velocities_{b}"], v, equal_nan=True)

"""Issue 36's second acceptance test: a scheduler and two workers started as separate processes
on 127.0.0.1 (as a real cluster is), the study run through the scheduler's address, from Python
and from the command line ($DASK_SCHEDULER_ADDRESS); and a worker killed while it runs a task,
whose task Dask gives to the other worker."""

import importlib.util
import json
import os
import signal
import subprocess
import sys
import threading
import time

import distributed
import pandas as pd
import pytest

from conftest import SOURCE_DIR
from study_support import assert_row_equals_serial, serial_run
from deformcd import study
from tiny_scenes import write_two_cubes

FRAMES = 12


def test_study_through_the_schedulers_address(separate_cluster, tmp_path):
    scene_file = write_two_cubes(tmp_path, frames=FRAMES)
    rows = study.run(scene_file, vary={"bodies.0.velocity.0": [1.0, 3.0],
                                       "settings.substeps": [4, 6]},
                     frames=FRAMES, scheduler=separate_cluster.address, log=None)
    assert len(rows) == 4 and (rows["status"] == "ok").all()
    assert rows["worker_pid"].isin([w.pid for w in separate_cluster.workers]).all()
    base = json.loads(scene_file.read_text())
    for _, row in rows.iterrows():
        scene = json.loads(json.dumps(base))
        scene["bodies"][0]["velocity"][0] = row["bodies.0.velocity.0"]
        scene["settings"]["substeps"] = int(row["settings.substeps"])
        assert_row_equals_serial(row.to_dict(), serial_run(scene, tmp_path, tmp_path, FRAMES))


def test_command_line_through_dask_scheduler_address(separate_cluster, tmp_path):
    scene_file = write_two_cubes(tmp_path, frames=FRAMES)
    out = tmp_path / "rows.csv"
    env = dict(os.environ, DASK_SCHEDULER_ADDRESS=separate_cluster.address)
    done = subprocess.run(
        [sys.executable, "-m", "deformcd.study", str(scene_file), "--vary",
         "bodies.0.velocity=[1,0,0],[2,0,0]", "--vary", "broadphase=bvh,brute", "--frames",
         str(FRAMES), "--out", str(out), "--no-census"], env=env, capture_output=True, text=True,
        timeout=120)
    assert done.returncode == 0, done.stderr
    assert f"on the cluster at {separate_cluster.address}" in done.stderr
    rows = pd.read_csv(out)
    assert list(rows["broadphase"]) == ["bvh", "brute", "bvh", "brute"]
    assert list(rows["bodies.0.velocity"]) == ["[1, 0, 0]", "[1, 0, 0]", "[2, 0, 0]", "[2, 0, 0]"]
    assert (rows["status"] == "ok").all()
    # every broad phase finds the same contacts: the same run bit for bit
    assert rows["state_hash"][0] == rows["state_hash"][1] != rows["state_hash"][2]
    per_frame = [json.loads(c) for c in rows["contacts_per_frame"]]
    assert per_frame[0] == per_frame[1] and len(per_frame[0]) == FRAMES
    assert rows["census_frames"].isna().all() and rows["max_self_pairs"].isna().all()


def test_parquet_is_refused_before_any_run_without_an_engine(tmp_path):
    if importlib.util.find_spec("pyarrow") or importlib.util.find_spec("fastparquet"):
        pytest.skip("a Parquet engine is installed: .parquet is written")
    scene_file = write_two_cubes(tmp_path)
    done = subprocess.run([sys.executable, "-m", "deformcd.study", str(scene_file),
                           "--out", str(tmp_path / "rows.parquet")],
                          capture_output=True, text=True, timeout=60)
    assert done.returncode == 2
    assert "Parquet needs pyarrow or fastparquet" in done.stderr
    assert "write CSV instead" in done.stderr and "local cluster" not in done.stderr


def test_a_killed_workers_task_is_run_again(separate_cluster, tmp_path):
    """phase2 (2,751 nodes, 30 frames) runs long enough on one thread (about half a second) to
    be killed in: the worker is killed as soon as the scheduler has given it a run."""
    scene_file = SOURCE_DIR / "scenes" / "phase2.json"
    vary = {"bodies.0.squash.0": [0.9, 0.92, 0.94, 0.96]}
    result, killed = {}, {}

    def study_thread():
        result["rows"] = study.run(scene_file, vary=vary, frames=30,
                                   scheduler=separate_cluster.address, log=None)

    runner = threading.Thread(target=study_thread)
    with distributed.Client(separate_cluster.address, timeout="30s") as watcher:
        pids = watcher.run(os.getpid)
        runner.start()
        deadline = time.monotonic() + 60
        while not killed and time.monotonic() < deadline:
            for address, keys in watcher.processing().items():
                runs = [int(str(k).split("-")[1]) for k in keys if "run_variation" in str(k)]
                if runs and pids[address] != os.getpid():
                    os.kill(pids[address], signal.SIGKILL)
                    killed.update(address=address, pid=pids[address], runs=runs)
                    break
            time.sleep(0.05)
    runner.join(timeout=120)
    assert killed, "no worker was seen running a task"
    rows = result["rows"]
    assert (rows["status"] == "ok").all(), rows["error"].tolist()
    for run in killed["runs"]:  # what it held was run again, by the other worker
        assert rows["worker_pid"][run] not in (killed["pid"], os.getpid())
    # the survivor ran what the killed one had: the same results as a run with nobody killed
    again = study.run(scene_file, vary={"bodies.0.squash.0": [0.9, 0.96]}, frames=30,
                      scheduler=separate_cluster.address, log=None)
    assert list(again["state_hash"]) == [rows["state_hash"][0], rows["state_hash"][3]]

"""Issue 36's first acceptance test: an 8-variation study on a 2-worker local cluster (the
default place a study runs), every row equal bit for bit to the same run done serially with
deformcd.World, and a variation that blows up a row with its error while the others complete."""

import copy
import json

from study_support import assert_row_equals_serial, serial_run
from deformcd import study
from tiny_scenes import write_two_cubes

FRAMES = 20
# Speeds, substeps, a stiffness, a perturbation and a broad phase; run 7 blows up (a stiffness
# a million times the stable one's at 1 substep).
VARIATIONS = [
    {"bodies.0.velocity.0": 0.5},
    {"bodies.0.velocity.0": 2.0},
    {"bodies.0.velocity.0": 2.0, "settings.substeps": 8},
    {"bodies.right.velocity": [-3, 0, 0]},
    {"bodies.*.material.stiffness": 30000},
    {"seed": 7, "perturb": 0.02},
    {"broadphase": "octree"},
    {"bodies.*.material.stiffness": 1e10, "settings.substeps": 1},
]


def varied_by_hand(scene, params):
    """The variation written out here, independently of the study's key paths."""
    s = copy.deepcopy(scene)
    left, right = s["bodies"]
    for key, value in params.items():
        if key == "bodies.0.velocity.0":
            left["velocity"][0] = value
        elif key == "bodies.right.velocity":
            right["velocity"] = value
        elif key == "bodies.*.material.stiffness":
            left["material"]["stiffness"] = right["material"]["stiffness"] = value
        elif key == "settings.substeps":
            s["settings"]["substeps"] = value
    if "seed" in params:
        import numpy as np

        rng = np.random.default_rng(params["seed"])
        for body in (left, right):
            body["position"] = [p + o for p, o in
                                zip(body["position"], rng.uniform(-0.02, 0.02, 3).tolist())]
    return s


def test_eight_variations_on_two_local_workers_equal_serial_runs(tmp_path):
    scene_file = write_two_cubes(tmp_path, frames=FRAMES)
    rows = study.run(scene_file, variations=VARIATIONS, frames=FRAMES, workers=2,
                     outputs=tmp_path / "outputs", out=tmp_path / "rows.csv", log=None)
    assert list(rows["run"]) == list(range(8))
    assert rows["worker_pid"].nunique() == 2  # both workers ran some, none of them this process
    base = json.loads(scene_file.read_text())
    for i, params in enumerate(VARIATIONS):
        row = rows.iloc[i].to_dict()
        serial = serial_run(varied_by_hand(base, params), tmp_path, tmp_path, FRAMES,
                            params.get("broadphase", "bvh"))
        assert_row_equals_serial(row, serial)
        if i < 7:
            assert row["status"] == "ok" and row["error"] is None, row["error"]
            assert row["frames"] == FRAMES and row["ms_per_frame_simulation"] > 0
            assert row["intersecting_frames"] == sum(n > 0 for n in serial["contacts_per_frame"])
            # the cubes pass into each other (no response): the census sees it too
            assert row["census_frames"] >= row["intersecting_frames"]
        else:
            e = serial["error"]
            assert e is not None, "run 7 was meant to blow up"
            assert row["status"] == "blew up" and row["error"] == str(e)
            assert (row["error_stage"], row["error_frame"], row["error_body"]) == \
                (e.stage, e.frame, e.body)
            assert row["error_frame"] == len(serial["contacts_per_frame"]) + 1
    # the cubes meet within the 20 frames, the faster one sooner
    assert 0 < rows.loc[1, "first_intersecting_frame"] < rows.loc[0, "first_intersecting_frame"]
    csv = (tmp_path / "rows.csv").read_text().splitlines()
    assert len(csv) == 9 and csv[0].startswith("run,bodies.0.velocity.0,")

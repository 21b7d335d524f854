"""deformcd.World from Python: a shipped scene stepped, its state and contacts as arrays, equal
to what `deformcd run` writes for the same frames."""

import json
import pickle
import subprocess

import numpy as np
import pytest

import deformcd
from conftest import SOURCE_DIR, contact_rows
from tiny_scenes import write_two_cubes

PHASE2 = SOURCE_DIR / "scenes" / "phase2.json"
FRAMES = 30


@pytest.fixture(scope="module")
def stepped():
    """phase2 on the CPU over 30 frames: the world after them, and each frame's contacts
    (frame 0, the initial pose, through detect())."""
    w = deformcd.World.from_scene(PHASE2, frames=FRAMES, backend="cpu", broadphase="bvh")
    assert w.frame == 0 and w.frames == FRAMES
    w.detect()
    per_frame = [w.contacts()]
    for _ in range(FRAMES):
        w.step()
        per_frame.append(w.contacts())
    return w, per_frame


def test_positions_velocities_faces_have_the_right_shapes(stepped):
    w, _ = stepped
    assert w.frame == FRAMES
    assert w.body_count == 2 and w.body_names == ["bunny", "dragon"]
    assert w.body_name(1) == "dragon" and w.backend == "cpu"
    nodes = 0
    for b in range(w.body_count):
        p, v, f = w.positions(b), w.velocities(b), w.faces(b)
        assert p.dtype == np.float32 and p.ndim == 2 and p.shape[1] == 3
        assert v.dtype == np.float32 and v.shape == p.shape
        assert f.ndim == 2 and f.shape[1] == 3 and f.min() >= 0 and f.max() < len(p)
        assert np.isfinite(p).all() and np.isfinite(v).all()
        nodes += len(p)
    assert nodes == 2751  # as `deformcd run` reports for phase2
    # the bodies moved toward each other along x (bunny from -x, dragon from +x)
    assert w.positions(0)[:, 0].mean() > -1.4775 + 0.1
    assert w.positions(1)[:, 0].mean() < 1.4775 - 0.1


def test_contacts_are_consistent_with_the_faces_and_flags(stepped):
    w, per_frame = stepped
    c = per_frame[-1]
    in_contact = [len(c["face_a"]) > 0 for c in per_frame]
    assert any(in_contact) and not in_contact[0]
    k = max(range(len(per_frame)), key=lambda i: len(per_frame[i]["face_a"]))
    c = per_frame[k]
    assert (c["body_a"] == 0).all() and (c["body_b"] == 1).all()
    np.testing.assert_array_equal(c["nodes_a"], w.faces(0)[c["face_a"]])
    np.testing.assert_array_equal(c["nodes_b"], w.faces(1)[c["face_b"]])
    last = per_frame[-1]
    flags = w.face_flags(0)
    assert flags.shape == (len(w.faces(0)),)
    assert set(np.flatnonzero(flags)) == set(last["face_a"].tolist())
    assert w.counts()["contacts"] == len(last["face_a"])


def test_every_frame_equals_deformcd_run(stepped, cli, tmp_path):
    w, per_frame = stepped
    contacts_file, positions_file = tmp_path / "contacts.jsonl", tmp_path / "positions.json"
    subprocess.run([cli, "run", str(PHASE2), "--backend", "cpu", "--broadphase", "bvh",
                    "--frames", str(FRAMES), "--contacts", str(contacts_file),
                    "--positions", str(positions_file)], check=True, capture_output=True)
    lines = [json.loads(line) for line in contacts_file.read_text().splitlines()]
    assert [line["frame"] for line in lines] == list(range(FRAMES + 1))
    for line, c in zip(lines, per_frame):
        expected = [[e["a"]["body"], e["a"]["face"], e["b"]["body"], e["b"]["face"]]
                    for e in line["contacts"]]
        assert contact_rows(c).tolist() == expected, f"frame {line['frame']}"
        for i, e in enumerate(line["contacts"]):
            if e.get("segment") is not None:
                np.testing.assert_array_equal(c["segment"][i], np.float32(e["segment"]))
    final = json.loads(positions_file.read_text())
    assert final["frame"] == FRAMES == w.frame
    for b, body in enumerate(final["bodies"]):
        assert body["name"] == w.body_name(b)
        np.testing.assert_array_equal(w.positions(b), np.float32(body["positions"]))


def test_broadphase_can_change_between_steps_and_agrees():
    w = deformcd.World.from_scene(str(PHASE2), frames=FRAMES, backend="cpu")
    w.step(13)  # in contact
    bvh = w.contacts()
    assert len(bvh["face_a"]) > 0
    w.broadphase = "octree"
    assert w.broadphase == "octree"
    w.detect()
    octree = w.contacts()
    for field in bvh:
        np.testing.assert_array_equal(octree[field], bvh[field])
    assert w.frame == 13
    assert "World" in repr(w) and "bunny" in repr(w)


def test_world_errors(tmp_path):
    with pytest.raises(deformcd.InputError, match="nothing.json"):
        deformcd.World.from_scene(tmp_path / "nothing.json")
    bad = tmp_path / "bad.json"
    bad.write_text('{"settings": {"dt": 0.01, "substepz": 2}, "bodies": []}')
    with pytest.raises(deformcd.InputError, match="substepz"):
        deformcd.World.from_scene(bad)
    with pytest.raises(ValueError, match="frames must be at least 1"):
        deformcd.World.from_scene(PHASE2, frames=0)
    with pytest.raises(deformcd.Error, match="bvh"):
        deformcd.World.from_scene(PHASE2, broadphase="kd-tree")
    w = deformcd.World.from_scene(PHASE2, frames=FRAMES, backend="cpu")
    with pytest.raises(IndexError, match="positions: body 2 does not exist"):
        w.positions(2)
    with pytest.raises(IndexError, match="asleep: body 2 does not exist"):
        w.asleep(2)
    with pytest.raises(ValueError, match="step: n must be 0 or more"):
        w.step(-1)
    surface_scene = tmp_path / "surface.json"
    (tmp_path / "tri.off").write_text("OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n"
                                      "3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n")
    surface_scene.write_text('{"bodies": [{"model": "tri.off"}]}')
    with pytest.raises(deformcd.InputError, match="TetGen"):
        deformcd.World.from_scene(surface_scene)


def test_stack_bodies_are_awake_while_they_fall():
    """The stack scene sleeps its resting bodies (response.sleep); falling, none is asleep (the
    C++ tests step it until it rests: tests/world/contact_response_test.cpp)."""
    w = deformcd.World.from_scene(SOURCE_DIR / "scenes" / "stack.json", frames=2, backend="cpu")
    w.step(2)
    assert [w.asleep(b) for b in range(len(w.body_names))] == [False] * 5


def test_blow_up_names_its_stage_frame_and_body(tmp_path):
    """SimulationError's attributes (what a study's row holds; SimulationError::site() in C++),
    agreeing with the message, and kept through pickle (Dask sends exceptions between
    processes)."""
    scene = json.loads(write_two_cubes(tmp_path).read_text())
    scene["settings"]["substeps"] = 1
    for body in scene["bodies"]:
        body["material"]["stiffness"] = 1e10  # a million times too stiff for one substep
    (tmp_path / "stiff.json").write_text(json.dumps(scene))
    w = deformcd.World.from_scene(tmp_path / "stiff.json", backend="cpu")
    with pytest.raises(deformcd.SimulationError) as info:
        w.step(20)
    e = info.value
    # the frame being stepped, or the one just stepped when the periodic check finds it
    assert e.stage == "simulation" and e.frame in (w.frame, w.frame + 1) and e.frame >= 1
    assert e.body in (0, 1) and e.body_name == w.body_name(e.body)
    assert f"body {e.body} ('{e.body_name}') by frame {e.frame}: node {e.node}" in str(e)
    again = pickle.loads(pickle.dumps(e))
    assert type(again) is deformcd.SimulationError and str(again) == str(e)
    assert (again.stage, again.frame, again.body, again.node) == (e.stage, e.frame, e.body, e.node)
    assert deformcd.SimulationError.frame is None  # a message naming no frame leaves None


def test_stage_times_and_response_counts(tmp_path):
    scene = json.loads(write_two_cubes(tmp_path, response=True).read_text())
    (tmp_path / "timed.json").write_text(json.dumps(scene))
    w = deformcd.World.from_scene(tmp_path / "timed.json", backend="cpu",
                                  measure_stage_times=True)
    assert w.last_frame_times() == {"simulation_s": 0.0, "collision_s": 0.0,
                                    "proximity_s": 0.0, "response_s": 0.0}
    pairs = []
    self_searches = 0
    substeps = scene["settings"]["substeps"]
    for _ in range(w.frames):
        w.step()
        c = w.response_counts()
        pairs.append(c["vertex_face"] + c["edge_edge"])
        assert c["between_bodies"] <= pairs[-1] + c["untangle"] + c["penetrating"]
        self_searches += c["self_searches"]
        assert c["penetrating"] == 0  # the cubes never start inside each other
        # the scene's substeps, more where substep_motion (0.3 by default) asks, up to 8 x
        assert substeps <= c["substeps"] <= 8 * substeps
        # 8 iterations a projection, more where a contact is still deep (up to 4 x)
        assert 8 * c["substeps"] <= c["iterations"] <= 32 * c["substeps"]
    # self-contact is on by default with a response: each cube searched against itself
    assert self_searches >= 2
    # without it, every contact constraint is between the two cubes, widenings included
    scene["collision"]["self"] = False
    (tmp_path / "no_self.json").write_text(json.dumps(scene))
    apart = deformcd.World.from_scene(tmp_path / "no_self.json", backend="cpu")
    between = []
    for _ in range(apart.frames):
        apart.step()
        c = apart.response_counts()
        assert c["self_searches"] == 0
        between.append(c["between_bodies"])
        assert between[-1] == c["vertex_face"] + c["edge_edge"] + c["untangle"] + c["penetrating"]
    assert max(between) > 0
    times = w.last_frame_times()
    assert times["simulation_s"] > 0 and times["collision_s"] > 0 and times["response_s"] > 0
    assert max(pairs) > 0 and w.counts()["contacts"] == 0  # the response kept them apart
    untimed = deformcd.World.from_scene(tmp_path / "timed.json", backend="cpu")
    untimed.step()
    assert untimed.last_frame_times()["simulation_s"] == 0.0


def test_intersection_census_counts_the_pairs_between_bodies_as_the_collision_pass_does():
    """phase2's bodies pass through each other (no response, no self-collision): on every frame
    the census's pairs between the bodies are the world's contacts, and once the bodies are
    inside each other some surface vertices are inside the other."""
    w = deformcd.World.from_scene(PHASE2, frames=60, backend="cpu", broadphase="bvh")
    most_inside = 0
    for _ in range(60):
        w.step()
        census = w.intersection_census()
        assert set(census) == {"between_pairs", "self_pairs", "inside_vertices"}
        assert census["between_pairs"] == w.counts()["contacts"]
        most_inside = max(most_inside, census["inside_vertices"])
    assert most_inside > 0


def test_gravity_can_change_between_steps(tmp_path):
    """Two cubes without gravity: given some along -y between steps, both fall as it says
    (before they meet), and a gravity that is not finite is an error that changes nothing."""
    w = deformcd.World.from_scene(write_two_cubes(tmp_path), backend="cpu")
    assert tuple(w.gravity) == (0.0, 0.0, 0.0)
    w.step()
    before = [w.velocities(b)[:, 1].mean() for b in range(w.body_count)]
    w.gravity = (0.0, -9.81, 0.0)
    assert w.gravity == pytest.approx((0.0, -9.81, 0.0))
    w.step()
    after = [w.velocities(b)[:, 1].mean() for b in range(w.body_count)]
    for b in range(w.body_count):
        assert after[b] - before[b] == pytest.approx(-9.81 / 60, rel=1e-3)
    with pytest.raises(deformcd.Error, match="gravity .*finite"):
        w.gravity = (0.0, float("nan"), 0.0)
    assert w.gravity == pytest.approx((0.0, -9.81, 0.0))

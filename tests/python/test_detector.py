"""deformcd.Detector from Python: contacts, every broad phase and input type agreeing, the
no-copy contract of set_positions, and errors."""

import json
import os
import subprocess
import sys
import threading

import numpy as np
import pytest

import deformcd
from conftest import contact_rows, pose

FIELDS = ("body_a", "face_a", "body_b", "face_b", "nodes_a", "nodes_b", "segment", "coplanar")


def assert_same_contacts(c, d):
    for field in FIELDS:
        np.testing.assert_array_equal(c[field], d[field], err_msg=field)


def test_issue_example_works_as_written(spheres):
    V0, F0, rest1, F1 = spheres
    V1 = pose(rest1, 0)
    V1_moved = pose(rest1, 15).astype(np.float64)
    d = deformcd.Detector([(V0, F0), (V1, F1)], backend="cpu", broadphase="bvh")
    d.set_positions(1, V1_moved)      # (n, 3) float32 or float64
    d.detect()
    c = d.contacts()
    k = len(c["body_a"])
    assert k > 0
    for field in ("body_a", "face_a", "body_b", "face_b"):
        assert c[field].shape == (k,) and c[field].dtype.kind == "i"
    assert c["segment"].shape == (k, 2, 3) and c["segment"].dtype == np.float32
    assert c["coplanar"].shape == (k,) and c["coplanar"].dtype == np.bool_
    assert c["nodes_a"].shape == (k, 3)
    assert (c["body_a"] == 0).all() and (c["body_b"] == 1).all()
    np.testing.assert_array_equal(c["nodes_a"], F0[c["face_a"]])
    np.testing.assert_array_equal(c["nodes_b"], F1[c["face_b"]])
    assert d.counts()["contacts"] == k


def test_two_triangles_crossing_give_the_segment_worked_out_by_hand():
    # A lies in the plane z = 0, B in the plane x = 0.25. B crosses z = 0 along its edge
    # (0, 1) at y = 0.1 and its edge (0, 2) at its midpoint, y = 0.4 (edge (1, 2) stays at
    # z = 1); A meets the line x = 0.25, z = 0 for y in [0, 0.75], which holds both points.
    A = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0]], np.float32)
    B = np.array([[0.25, 0.1, -1], [0.25, 0.1, 1], [0.25, 0.7, 1]], np.float32)
    d = deformcd.Detector([(A, [[0, 1, 2]]), (B, [[0, 1, 2]])], backend="cpu")
    d.detect()
    c = d.contacts()
    assert contact_rows(c).tolist() == [[0, 0, 1, 0]]
    assert not c["coplanar"][0]
    ends = sorted(map(tuple, c["segment"][0].tolist()))
    np.testing.assert_allclose(ends, [(0.25, 0.1, 0.0), (0.25, 0.4, 0.0)], atol=1e-6)
    np.testing.assert_array_equal(d.face_flags(), [True, True])


@pytest.mark.parametrize("frame", [0, 9, 12, 15, 20])
def test_every_broadphase_and_float32_float64_input_find_the_same_contacts(spheres, frame):
    V0, F0, rest1, F1 = spheres
    V1 = pose(rest1, frame)
    results = {}
    for method in deformcd.broadphases:
        for dtype in (np.float32, np.float64):
            d = deformcd.Detector([(V0.astype(dtype), F0), (V1.astype(dtype), F1)],
                                  backend="cpu", broadphase=method)
            assert d.broadphase == method
            d.detect()
            results[(method, dtype)] = d.contacts()
    reference = results[("brute", np.float32)]
    assert (len(reference["body_a"]) > 0) == (9 <= frame <= 20)
    for key, c in results.items():
        assert_same_contacts(c, reference)


def gl_detector(meshes, **options):
    """A detector on the GL backend, or skip (a failure under DEFORMCD_REQUIRE_GL=1, as the C++
    GL tests) when no OpenGL 4.3 context can be had."""
    if not deformcd.has_gl:
        pytest.skip("this deformcd module was built without the GL backend")
    try:
        return deformcd.Detector(meshes, backend="gl", **options)
    except deformcd.GlError as e:
        if os.environ.get("DEFORMCD_REQUIRE_GL") == "1":
            raise
        pytest.skip(f"no OpenGL 4.3 context: {e}")


@pytest.mark.parametrize("method", deformcd.broadphases)
def test_the_gl_backend_finds_the_cpu_contacts(spheres, method):
    V0, F0, rest1, F1 = spheres
    V1 = pose(rest1, 12)
    gl = gl_detector([(V0, F0), (V1, F1)], broadphase=method)
    assert gl.backend == "gl"
    gl.detect()
    cpu = deformcd.Detector([(V0, F0), (V1, F1)], backend="cpu", broadphase=method)
    cpu.detect()
    assert len(cpu.contacts()["face_a"]) > 0
    assert_same_contacts(gl.contacts(), cpu.contacts())
    np.testing.assert_array_equal(gl.face_flags(), cpu.face_flags())
    V1[:] = pose(rest1, 15)  # read in place on GL too (uploaded by each detect())
    gl.detect()
    cpu.detect()
    assert_same_contacts(gl.contacts(), cpu.contacts())


def test_contacts_match_segment_geometry_and_face_flags(spheres):
    # Each segment end lies on both triangles (in their planes, inside them): the pairs
    # reported really intersect, checked with nothing of the detector's.
    V0, F0, rest1, F1 = spheres
    V1 = pose(rest1, 12)
    d = deformcd.Detector([(V0, F0), (V1, F1)], backend="cpu")
    d.detect()
    c = d.contacts()
    assert len(c["face_a"]) > 50

    def on_triangle(points, tri):
        a, b, e = (tri[:, i].astype(np.float64) for i in range(3))
        n = np.cross(b - a, e - a)
        area2 = np.linalg.norm(n, axis=1)
        n /= area2[:, None]
        dist = np.abs(np.einsum("ij,ij->i", points - a, n))
        # barycentric coordinates through sub-areas
        w = [np.einsum("ij,ij->i", np.cross(q - p, points - p), n) / area2
             for p, q in ((a, b), (b, e), (e, a))]
        return (dist < 1e-5) & (np.min(w, axis=0) > -1e-4)

    for end in (0, 1):
        p = c["segment"][:, end].astype(np.float64)
        assert on_triangle(p, V0[F0[c["face_a"]]]).all()
        assert on_triangle(p, V1[F1[c["face_b"]]]).all()
    flags0 = np.zeros(len(F0), bool)
    flags0[c["face_a"]] = True
    flags1 = np.zeros(len(F1), bool)
    flags1[c["face_b"]] = True
    np.testing.assert_array_equal(d.face_flags(0), flags0)
    np.testing.assert_array_equal(d.face_flags(1), flags1)
    np.testing.assert_array_equal(d.face_flags(), np.concatenate([flags0, flags1]))
    assert d.face_offset(1) == len(F0)
    assert d.counts()["colliding_faces"] == flags0.sum() + flags1.sum()


def test_contacts_equal_the_cli_collide_on_the_same_files(spheres, cli, tmp_path):
    V0, F0, rest1, F1 = spheres
    V1 = pose(rest1, 14)
    files = []
    for i, (V, F) in enumerate(((V0, F0), (V1, F1))):
        path = tmp_path / f"mesh{i}.off"
        with open(path, "w") as f:
            f.write(f"OFF\n{len(V)} {len(F)} 0\n")
            np.savetxt(f, V.astype(np.float64), fmt="%.9g")
            np.savetxt(f, np.hstack([np.full((len(F), 1), 3), F]), fmt="%d")
        files.append(path)
    out = tmp_path / "contacts.json"
    subprocess.run([cli, "collide", *map(str, files), "--backend", "cpu", "--json", str(out)],
                   check=True, capture_output=True)
    expected = json.loads(out.read_text())["contacts"]
    assert len(expected) > 50

    meshes = [deformcd.read_surface(p) for p in files]
    np.testing.assert_array_equal(meshes[0][1], F0)
    d = deformcd.Detector(meshes, backend="cpu")  # float64 from the files: one conversion
    d.detect()
    c = d.contacts()
    assert contact_rows(c).tolist() == [[e["a"]["body"], e["a"]["face"], e["b"]["body"],
                                         e["b"]["face"]] for e in expected]
    assert c["nodes_a"].tolist() == [e["a"]["nodes"] for e in expected]
    for i, e in enumerate(expected):
        assert bool(c["coplanar"][i]) == e.get("coplanar", False)
        if e.get("segment") is not None:  # the CLI prints floats that read back the same
            np.testing.assert_array_equal(c["segment"][i], np.float32(e["segment"]))


def test_float32_c_contiguous_positions_are_read_in_place_and_held(spheres):
    V0, F0, rest1, F1 = spheres
    far = pose(rest1, 0)  # apart
    d = deformcd.Detector([(V0, F0), (far.copy(), F1)], backend="cpu")
    V1 = far.copy()
    before = sys.getrefcount(V1)
    d.set_positions(1, V1)
    assert d.positions(1) is V1  # no copy: the caller's object is the one read
    assert sys.getrefcount(V1) == before + 1  # and the detector holds a reference to it
    d.detect()
    assert d.counts()["contacts"] == 0
    V1[:] = pose(rest1, 12)  # in place, no set_positions: the next detect() reads it
    d.detect()
    in_contact = d.contacts()
    assert len(in_contact["face_a"]) > 0
    V1[:] = far
    d.detect()
    assert d.counts()["contacts"] == 0
    d.set_positions(1, far)
    assert sys.getrefcount(V1) == before  # released by the next set_positions of the mesh


def test_vertices_given_at_construction_are_the_positions_until_set(spheres):
    V0, F0, rest1, F1 = spheres
    V1 = pose(rest1, 0)
    d = deformcd.Detector([(V0, F0), (V1, F1)], backend="cpu")
    assert d.positions(0) is V0 and d.positions(1) is V1
    d.detect()
    assert d.counts()["contacts"] == 0
    V1[:] = pose(rest1, 12)
    d.detect()
    assert d.counts()["contacts"] > 0


def test_row_strided_float32_is_read_in_place_other_layouts_are_copied_once(spheres):
    V0, F0, rest1, F1 = spheres
    d = deformcd.Detector([(V0, F0), (rest1, F1)], backend="cpu")
    V4 = np.zeros((len(rest1), 4), np.float32)  # xyzw rows, as a GPU vec4 buffer
    V4[:, :3] = pose(rest1, 0)
    view = V4[:, :3]
    d.set_positions(1, view)
    assert d.positions(1) is view  # a view of V4: read in place with a 16-byte stride
    d.detect()
    assert d.counts()["contacts"] == 0
    V4[:, :3] = pose(rest1, 12)
    d.detect()
    strided_contacts = d.contacts()
    assert len(strided_contacts["face_a"]) > 0

    for other in (pose(rest1, 12).astype(np.float64),            # float64
                  np.asfortranarray(pose(rest1, 12)),             # column-major
                  pose(rest1, 12).astype(">f4"),                  # big-endian
                  pose(rest1, 12).tolist()):                      # a list
        d.set_positions(1, other)
        held = d.positions(1)
        assert held is not other
        assert held.dtype == np.float32 and held.flags.c_contiguous and held.flags.owndata
        d.detect()
        assert_same_contacts(d.contacts(), strided_contacts)
    V64 = pose(rest1, 12).astype(np.float64)
    d.set_positions(1, V64)
    V64[:] = pose(rest1, 0)  # the copy was made at set_positions: this changes nothing
    d.detect()
    assert_same_contacts(d.contacts(), strided_contacts)


def test_positions_of_the_wrong_shape_or_dtype_are_value_errors(spheres):
    V0, F0, rest1, F1 = spheres
    d = deformcd.Detector([(V0, F0), (rest1, F1)], backend="cpu")
    n = len(rest1)
    with pytest.raises(ValueError) as e:
        d.set_positions(1, np.zeros((n - 2, 3), np.float32))
    assert str(e.value) == ("set_positions: positions must have shape (n, 3) with n = "
                            f"{n} vertices of mesh 1, got ({n - 2}, 3)")
    with pytest.raises(ValueError, match=r"got \(642, 4\)"):
        d.set_positions(1, np.zeros((n, 4), np.float32))
    with pytest.raises(ValueError, match=r"got \(1926,\)"):
        d.set_positions(1, np.zeros(3 * n, np.float32))
    with pytest.raises(ValueError, match="positions must be float32 or float64, got int64"):
        d.set_positions(1, np.zeros((n, 3), np.int64))
    with pytest.raises(ValueError, match="got float16"):
        d.set_positions(1, np.zeros((n, 3), np.float16))
    assert d.positions(1) is rest1  # unchanged after every failure


def test_meshes_of_the_wrong_shape_or_dtype_are_value_errors():
    V = np.zeros((3, 3), np.float32)
    with pytest.raises(ValueError, match=r"meshes\[0\] faces must be an integer array, got "
                                         r"float64"):
        deformcd.Detector([(V, np.zeros((1, 3)))])
    with pytest.raises(ValueError, match=r"meshes\[1\] faces must have shape \(m, 3\), got "
                                         r"\(1, 4\)"):
        deformcd.Detector([(V, [[0, 1, 2]]), (V, [[0, 1, 2, 0]])])
    with pytest.raises(ValueError, match=r"meshes\[0\] vertices must have shape \(n, 3\), got "
                                         r"\(3, 2\)"):
        deformcd.Detector([(np.zeros((3, 2)), [[0, 1, 2]])])
    with pytest.raises(ValueError, match=r"meshes\[0\] must be a \(vertices, faces\) pair"):
        deformcd.Detector([V])
    with pytest.raises(ValueError, match="unknown key 'self'"):
        deformcd.Detector([{"vertices": V, "faces": [[0, 1, 2]], "self": True}])
    with pytest.raises(ValueError, match=r"mesh_pairs\[0\] must be a pair"):
        deformcd.Detector([(V, [[0, 1, 2]])], mesh_pairs=[(0, 1, 2)])
    with pytest.raises(ValueError, match="mesh_pairs must be None or a sequence"):
        deformcd.Detector([(V, [[0, 1, 2]])], mesh_pairs=5)


def test_input_errors_carry_the_detectors_messages(spheres):
    V = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0]], np.float32)
    with pytest.raises(deformcd.InputError) as e:
        deformcd.Detector([(V, [[0, 1, 2]]), (V, [[0, 1, 2], [2, 1, 0], [0, 1, 3]])])
    assert str(e.value) == ("mesh 1: triangle 2 (0, 1, 3) has vertex index 3, out of range (the "
                            "mesh has 3 vertices)")
    with pytest.raises(deformcd.InputError,
                       match=r"^mesh 0 \('cloth'\): triangle 0 \(0, -1, 2\) has vertex index -1"):
        deformcd.Detector([{"vertices": V, "faces": [[0, -1, 2]], "name": "cloth"}])
    with pytest.raises(deformcd.InputError, match="^mesh 0: has no triangles"):
        deformcd.Detector([(V, np.zeros((0, 3), int))])
    with pytest.raises(deformcd.InputError, match="mesh_pairs|mesh pairs"):
        deformcd.Detector([(V, [[0, 1, 2]])], mesh_pairs=[(0, 4)])

    V0, F0, rest1, F1 = spheres
    V1 = pose(rest1, 12)
    d = deformcd.Detector([(V0, F0), (V1, F1)], backend="cpu")
    d.detect()
    before = d.contacts()
    V1[17, 1] = np.nan
    with pytest.raises(deformcd.InputError) as e:
        d.detect()
    assert str(e.value).startswith("mesh 1: vertex 17 has a non-finite position")
    assert_same_contacts(d.contacts(), before)  # the last results stay
    with pytest.raises(deformcd.InputError, match="^set_positions: mesh 2 does not exist "
                                                  r"\(there are 2 meshes\)"):
        d.set_positions(2, V1)
    with pytest.raises(IndexError, match="mesh -1 does not exist"):
        d.positions(-1)


def test_error_classes_and_other_errors():
    assert issubclass(deformcd.Error, RuntimeError)
    for cls in (deformcd.InputError, deformcd.GlError, deformcd.SimulationError):
        assert issubclass(cls, deformcd.Error)
    V = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0]], np.float32)
    with pytest.raises(deformcd.Error, match="bvh"):  # the message lists the valid names
        deformcd.Detector([(V, [[0, 1, 2]])], broadphase="kd-tree")
    with pytest.raises(deformcd.Error, match="cpu"):
        deformcd.Detector([(V, [[0, 1, 2]])], backend="cuda")
    with pytest.raises(deformcd.Error, match="threads"):
        deformcd.Detector([(V, [[0, 1, 2]])], threads=-1)
    if not deformcd.has_gl:
        with pytest.raises(deformcd.GlError, match="without the OpenGL backend"):
            deformcd.Detector([(V, [[0, 1, 2]])], backend="gl")


def test_thread_counts_past_the_limit_raise_the_librarys_input_error():
    # Issue 34: 2**31-1 threads killed the interpreter inside oneTBB.
    V = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0]], np.float32)
    assert deformcd.Detector([(V, [[0, 1, 2]])], backend="cpu", threads=256)
    for threads in (257, 2**31 - 1, -1):
        expected = ("threads: must be 0 (every core) or 1 to 256 (deformcd::kMaxThreads), got "
                    + str(threads))
        with pytest.raises(deformcd.InputError) as raised:
            deformcd.Detector([(V, [[0, 1, 2]])], backend="cpu", threads=threads)
        assert str(raised.value) == expected


def test_faces_too_large_to_convert_raise_memory_error():
    # Issue 34: a broadcast view of 2**40 faces needs 24 TB as int64; numpy's MemoryError must
    # reach the caller, not "error_already_set called while Python error indicator not set".
    V = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0]], np.float32)
    faces = np.broadcast_to(np.array([0, 1, 2], np.int32), (2**40, 3))
    with pytest.raises(MemoryError):
        deformcd.Detector([(V, faces)], backend="cpu")


def test_self_collision_and_mesh_pairs(spheres):
    V0, F0, rest1, F1 = spheres
    V1 = pose(rest1, 12)
    two = deformcd.Detector([(V0, F0), (V1, F1)], backend="cpu")
    two.detect()
    c2 = two.contacts()
    # The same two spheres as one mesh with self-collision: the same pairs, within mesh 0.
    merged = {"vertices": np.vstack([V0, V1]), "faces": np.vstack([F0, F1 + len(V0)]),
              "self_collision": True}
    for method in deformcd.broadphases:
        one = deformcd.Detector([merged], backend="cpu", broadphase=method)
        one.detect()
        c1 = one.contacts()
        assert (c1["body_a"] == 0).all() and (c1["body_b"] == 0).all()
        np.testing.assert_array_equal(c1["face_a"], c2["face_a"])
        np.testing.assert_array_equal(c1["face_b"], c2["face_b"] + len(F0))
        np.testing.assert_array_equal(c1["segment"], c2["segment"])
    # mesh_pairs leaves a pair out; (m, m) asks for a mesh with itself.
    three = deformcd.Detector([(V0, F0), (V1, F1), (V1.copy(), F1)], backend="cpu",
                              mesh_pairs=[(0, 1)])
    three.detect()
    assert_same_contacts(three.contacts(), c2)
    self_pair = deformcd.Detector([merged | {"self_collision": False}], mesh_pairs=[(0, 0)],
                                  backend="cpu")
    self_pair.detect()
    assert self_pair.counts()["contacts"] == len(c2["face_a"])


def test_broadphase_threads_and_properties(spheres):
    V0, F0, rest1, F1 = spheres
    V1 = pose(rest1, 12)
    d = deformcd.Detector([(V0, F0), (V1, F1)], backend="cpu", threads=1, broadphase="none")
    assert (d.mesh_count, d.face_count, d.vertex_count(1)) == (2, 2 * len(F0), len(V1))
    np.testing.assert_array_equal(d.faces(1), F1)
    assert d.backend == "cpu" and "1 thread" in d.device and d.notice == ""
    d.detect()
    assert len(d.contacts()["face_a"]) == 0 and d.counts()["contacts"] == 0
    d.broadphase = "octree"
    d.detect()
    one_thread = d.contacts()
    many = deformcd.Detector([(V0, F0), (V1, F1)], backend="cpu", threads=2)
    many.detect()
    assert_same_contacts(many.contacts(), one_thread)
    assert "Detector" in repr(d) and "octree" in repr(d)
    assert d.counts()["box_pairs"] > 0


def test_contacts_before_the_first_detect_are_empty_arrays(spheres):
    V0, F0, rest1, F1 = spheres
    d = deformcd.Detector([(V0, F0), (rest1, F1)], backend="cpu")
    c = d.contacts()
    assert set(c) == set(FIELDS)
    assert c["segment"].shape == (0, 2, 3) and c["face_a"].shape == (0,)
    assert d.counts() == {"contacts": 0, "box_pairs": 0, "colliding_faces": 0, "candidates": 0}
    assert not d.face_flags().any()


def test_calls_from_several_threads_run_one_at_a_time(spheres):
    V0, F0, rest1, F1 = spheres
    V1 = pose(rest1, 12)
    d = deformcd.Detector([(V0, F0), (V1, F1)], backend="cpu", broadphase="brute")
    d.detect()
    expected = d.counts()["contacts"]
    errors = []

    def worker():
        try:
            for _ in range(5):
                d.set_positions(1, V1.astype(np.float64))  # drops the array a pass may read
                d.detect()
                assert d.counts()["contacts"] == expected
        except Exception as e:  # noqa: BLE001 (reported below)
            errors.append(e)

    threads = [threading.Thread(target=worker) for _ in range(3)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert errors == []


def test_read_surface(tmp_path):
    off = tmp_path / "quad.off"
    off.write_text("OFF\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n")
    V, F = deformcd.read_surface(off)
    assert V.dtype == np.float64 and V.shape == (4, 3)
    np.testing.assert_array_equal(F, [[0, 1, 2], [0, 2, 3]])  # fan-triangulated
    bad = tmp_path / "bad.off"
    bad.write_text("OFF\n4 1 0\n0 0 0\n1 0 0\n")
    with pytest.raises(deformcd.InputError, match="bad.off"):
        deformcd.read_surface(str(bad))


def test_help_documents_every_call():
    for cls in (deformcd.Detector, deformcd.World):
        for name, member in vars(cls).items():
            if not name.startswith("_"):
                assert (member.__doc__ or "").strip(), f"{cls.__name__}.{name} has no docstring"
    assert "set_positions" in deformcd.Detector.__doc__
    assert "in place" in deformcd.Detector.set_positions.__doc__


def test_no_reference_or_memory_leak_over_a_thousand_calls(spheres):
    import gc
    import tracemalloc
    V0, F0, rest1, F1 = spheres
    d = deformcd.Detector([(V0, F0), (pose(rest1, 12), F1)], backend="cpu")
    frames = [pose(rest1, 12), pose(rest1, 12).astype(np.float64)]
    refs = [sys.getrefcount(f) for f in frames]

    def calls(n):
        for i in range(n):
            d.set_positions(1, frames[i % 2])
            d.detect()
            c = d.contacts()
            assert len(c["face_a"]) > 0
            d.counts()
            d.face_flags()

    calls(50)  # warm-up: pools, lists that keep their capacity
    gc.collect()
    tracemalloc.start()
    before = tracemalloc.take_snapshot()
    calls(1000)
    gc.collect()
    after = tracemalloc.take_snapshot()
    tracemalloc.stop()
    grown = sum(s.size_diff for s in after.compare_to(before, "filename"))
    assert grown < 64 * 1024, f"Python-side memory grew by {grown} bytes over 1,000 calls"
    d.set_positions(1, pose(rest1, 0))  # releases the last array it held
    assert [sys.getrefcount(f) for f in frames] == refs

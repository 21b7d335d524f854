"""The README's Python example, run as it is printed there (keep them in step)."""

import numpy as np

from conftest import SOURCE_DIR


def readme_example():
    # README example begins
    import numpy as np
    import deformcd

    bunny = deformcd.read_surface("assets/models/surfaces/bunny.off")  # V float64 (n, 3), F (m, 3)
    V, F = deformcd.read_surface("assets/models/surfaces/dragon.off")
    V = V.astype(np.float32) + np.float32([1.2, 0, 0])  # float32, C-contiguous: read in place
    d = deformcd.Detector([bunny, (V, F)], backend="cpu", broadphase="bvh")
    for frame in range(48):
        V[:, 0] -= 0.05  # moves the dragon: detect() reads V where it is
        d.detect()
        c = d.contacts()  # NumPy arrays, one row per intersecting triangle pair
        if frame % 8 == 0:
            print(f"frame {frame}: {len(c['face_a'])} pairs, "
                  f"{d.face_flags(0).sum()} bunny triangles in contact")

    w = deformcd.World.from_scene("scenes/phase2.json", frames=60, backend="cpu")
    w.step(30)
    print(w.body_names, w.positions(0).shape, w.counts()["contacts"], "contacts at frame", w.frame)
    # README example ends
    return d, w


def test_readme_example_runs(monkeypatch, capsys):
    monkeypatch.chdir(SOURCE_DIR)
    d, w = readme_example()
    out = capsys.readouterr().out
    print(out)
    assert "frame 24:" in out
    pairs = [int(line.split()[2]) for line in out.splitlines() if line.startswith("frame")]
    assert pairs[0] == 0 and max(pairs) > 0  # apart at first, then through each other
    assert w.frame == 30 and w.positions(0).shape[1] == 3
    assert isinstance(d.contacts()["segment"], np.ndarray)

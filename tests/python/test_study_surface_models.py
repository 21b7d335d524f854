"""Surface models in a study: meshed once per distinct model by `deformcd tetra` (a separate
process: TetGen is AGPL-3 and not in the module), cached by content, and the runs done on the
cached TetGen files, equal to serial World runs on them."""

import json
import sys

import pytest

from conftest import SOURCE_DIR
from study_support import assert_row_equals_serial, serial_run
from deformcd import study
from tiny_scenes import write_two_cubes

sys.path.insert(0, str(SOURCE_DIR / "examples"))
from compare_broadphases import icosphere  # noqa: E402

FRAMES = 8


def write_ball(path, radius=0.1):
    V, F = icosphere(1, radius)
    lines = ["OFF", f"{len(V)} {len(F)} 0"]
    lines += [" ".join(repr(float(x)) for x in v) for v in V]
    lines += ["3 " + " ".join(str(int(i)) for i in f) for f in F]
    path.write_text("\n".join(lines) + "\n")


def test_surface_model_is_meshed_once_and_cached(separate_cluster, cli, tmp_path):
    write_ball(tmp_path / "ball.off")
    scene_file = write_two_cubes(tmp_path, frames=FRAMES, model="ball.off")
    cache = tmp_path / "cache"
    messages = []
    vary = {"bodies.0.velocity.0": [1.0, 2.0, 4.0]}
    rows = study.run(scene_file, vary=vary, frames=FRAMES, scheduler=separate_cluster.address,
                     cli=cli, cache_dir=cache, log=messages.append)
    meshing = [m for m in messages if "meshing ball.off once" in m]
    assert len(meshing) == 1, messages  # two bodies, three runs: one mesh
    assert "--quality 2.0 --preserve-surface" in meshing[0]  # the scene's default meshing
    (entry,) = [p for p in cache.iterdir() if not p.name.startswith(".")]
    prefix = entry / "ball"
    assert (entry / "done").is_file() and prefix.with_suffix(".node").is_file()
    assert (rows["status"] == "ok").all(), rows["error"].tolist()
    base = json.loads(scene_file.read_text())
    for _, row in rows.iterrows():
        scene = json.loads(json.dumps(base))
        for body in scene["bodies"]:
            body["model"] = str(prefix)
        scene["bodies"][0]["velocity"][0] = row["bodies.0.velocity.0"]
        assert_row_equals_serial(row.to_dict(), serial_run(scene, tmp_path, tmp_path, FRAMES))
    # a second study finds the mesh in the cache; another meshing is another entry
    messages.clear()
    again = study.run(scene_file, frames=FRAMES, scheduler=separate_cluster.address, cli=cli,
                      cache_dir=cache, log=messages.append)
    assert any("ball.off: meshed before" in m for m in messages), messages
    assert not any("meshing" in m for m in messages)
    assert again["state_hash"][0] == rows["state_hash"][0]


def test_surface_model_without_the_tool_is_a_clear_error(tmp_path, monkeypatch):
    write_ball(tmp_path / "ball.off")
    scene_file = write_two_cubes(tmp_path, model="ball.off")
    monkeypatch.delenv("DEFORMCD_CLI", raising=False)
    monkeypatch.setenv("PATH", str(tmp_path))
    with pytest.raises(FileNotFoundError, match=r"bodies/0/model: .*ball.off is a surface model"):
        study.run(scene_file, cache_dir=tmp_path / "cache", log=None)

"""A study's variations: --vary's values, the grid, the key paths and their errors."""

import pytest

from deformcd.study import variations


def test_parse_vary_reads_json_values_and_bare_strings():
    assert variations.parse_vary("settings.substeps=8,16") == ("settings.substeps", [8, 16])
    assert variations.parse_vary("bodies.0.velocity=[1,0,0],[2.5,0,0]") == \
        ("bodies.0.velocity", [[1, 0, 0], [2.5, 0, 0]])
    assert variations.parse_vary("broadphase=bvh,octree") == ("broadphase", ["bvh", "octree"])
    assert variations.parse_vary("response.thickness=1e-3") == ("response.thickness", [0.001])
    with pytest.raises(ValueError, match="expected KEY=VALUE"):
        variations.parse_vary("settings.substeps")


def test_grid_varies_the_last_key_fastest():
    runs = variations.expand({"a": [1, 2], "b": ["x", "y", "z"]})
    assert runs[:3] == [{"a": 1, "b": "x"}, {"a": 1, "b": "y"}, {"a": 1, "b": "z"}]
    assert len(runs) == 6 and variations.expand() == [{}]
    with pytest.raises(ValueError, match="not both"):
        variations.expand({"a": [1]}, [{"a": 1}])
    with pytest.raises(ValueError, match="must be a list"):
        variations.expand({"a": 3})


def test_apply_sets_keys_by_index_name_and_wildcard_without_changing_the_base():
    base = {"settings": {"substeps": 4},
            "bodies": [{"name": "a", "velocity": [1, 0, 0], "material": {"stiffness": 1}},
                       {"name": "b", "velocity": [0, 0, 0], "material": {"stiffness": 2}}]}
    scene, run = variations.apply(base, {"bodies.b.velocity.1": 5, "bodies.*.material.damping":
                                         0.1, "settings.substeps": 8, "frames": 3,
                                         "broadphase": "octree"})
    assert scene["bodies"][1]["velocity"] == [0, 5, 0] and scene["settings"]["substeps"] == 8
    assert [b["material"]["damping"] for b in scene["bodies"]] == [0.1, 0.1]
    assert run == {"frames": 3, "broadphase": "octree"}
    assert scene["collision"]["broadphase"] == "octree"
    assert base["settings"]["substeps"] == 4 and "damping" not in base["bodies"][0]["material"]
    with pytest.raises(ValueError, match="index 2 is out of range"):
        variations.apply(base, {"bodies.2.velocity": [0, 0, 0]})
    with pytest.raises(ValueError, match="neither an index nor a body name"):
        variations.apply(base, {"bodies.c.velocity": [0, 0, 0]})
    with pytest.raises(ValueError, match="no 'position' in the scene to index into"):
        variations.apply(base, {"bodies.0.position.0": 1.0})
    with pytest.raises(ValueError, match="no 'setings' section"):
        variations.apply(base, {"setings.substeps": 2})


def test_perturbation_is_the_seeds_and_needs_both_keys():
    base = {"bodies": [{"position": [0, 0, 0]}, {"position": [1, 0, 0]}]}
    one, _ = variations.apply(base, {"seed": 3, "perturb": 0.01})
    two, _ = variations.apply(base, {"seed": 3, "perturb": 0.01})
    other, _ = variations.apply(base, {"seed": 4, "perturb": 0.01})
    assert one == two != other
    assert all(abs(p) <= 0.01 for p in one["bodies"][0]["position"])
    with pytest.raises(ValueError, match="needs both seed and perturb"):
        variations.apply(base, {"seed": 3})

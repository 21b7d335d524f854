"""A study's variations: which runs (a grid or a list), each as the base scene with some keys
changed. Runs only on the client: the workers receive finished scenes.

A key is a dotted path into the scene's JSON: "settings.substeps", "response.restitution",
"bodies.0.velocity", "bodies.lion.material.stiffness" (a body by index or by name),
"bodies.*.material.damping" (every body), "bodies.0.velocity.0" (one component). Run keys are
not in the scene: "frames" (the run's length), "broadphase" (the collision pass after each
frame), "seed" and "perturb" (each body's position moved by a uniform offset in
[-perturb, perturb] per axis, drawn from numpy.random.default_rng(seed): body by body, x y z).
"""

import copy
import itertools
import json

import numpy as np

RUN_KEYS = ("frames", "broadphase", "seed", "perturb")


def parse_vary(text):
    """"key=v1,v2,..." (the command line's --vary) -> (key, [values]). Values are JSON where
    they parse as JSON ("8", "1e4", "[1.5,0,0]", "true"), strings otherwise ("bvh");
    "key=[1,0,0],[2,0,0]" is two vectors."""
    key, sep, values = text.partition("=")
    key = key.strip()
    if not sep or not key or not values.strip():
        raise ValueError(f"--vary {text!r}: expected KEY=VALUE[,VALUE...], e.g. "
                         f"settings.substeps=8,16")
    try:
        parsed = json.loads("[" + values + "]")
    except json.JSONDecodeError:
        parsed = [_scalar(v) for v in _split_top_level(values)]
    if not parsed:
        raise ValueError(f"--vary {text!r}: no values")
    return key, parsed


def _scalar(text):
    text = text.strip()
    try:
        return json.loads(text)
    except json.JSONDecodeError:
        return text


def _split_top_level(text):
    """Splits at the commas outside brackets."""
    parts, depth, start = [], 0, 0
    for i, ch in enumerate(text):
        depth += ch == "["
        depth -= ch == "]"
        if ch == "," and depth == 0:
            parts.append(text[start:i])
            start = i + 1
    parts.append(text[start:])
    return parts


def expand(vary=None, variations=None):
    """The runs' parameters, a list of {key: value} in run order: the grid over `vary`
    ({key: [values]}, the last key varying fastest) or the list `variations`; one run of the
    base scene when neither is given."""
    if vary and variations is not None:
        raise ValueError("give either vary (a grid) or variations (a list), not both")
    if variations is not None:
        runs = [dict(v) for v in variations]
        if not runs:
            raise ValueError("variations is an empty list: no run to do")
        return runs
    if not vary:
        return [{}]
    keys = list(vary)
    for key in keys:
        if isinstance(vary[key], (str, bytes)) or not hasattr(vary[key], "__iter__"):
            raise ValueError(f"vary[{key!r}] must be a list of values, got {vary[key]!r}")
    return [dict(zip(keys, combo)) for combo in itertools.product(*(list(vary[k]) for k in keys))]


def apply(scene, params):
    """The scene (a dict, not changed) with the parameters' scene keys set, and the run keys
    {frames, broadphase} the runner needs. Raises ValueError naming a key whose path does not
    exist in the scene (a new key in an existing object is allowed: the scene reader rejects
    unknown ones with the file and the key)."""
    varied = copy.deepcopy(scene)
    run = {}
    for key, value in params.items():
        if key in ("frames", "broadphase"):
            run[key] = value
        elif key not in ("seed", "perturb"):
            _set(varied, key, value)
    if "perturb" in params or "seed" in params:
        _perturb(varied, params.get("seed"), params.get("perturb"))
    if "broadphase" in run:  # the scene's own names it too, and its reader checks the name
        varied.setdefault("collision", {})["broadphase"] = run["broadphase"]
    return varied, run


def _set(scene, key, value):
    parts = key.split(".")
    if parts[0] not in ("settings", "collision", "response", "bodies"):
        raise ValueError(f"vary key {key!r}: a scene has no {parts[0]!r} section (settings, "
                         f"collision, response, bodies), and {key!r} is not a run key "
                         f"({', '.join(RUN_KEYS)})")
    targets = [scene]
    for depth, part in enumerate(parts[:-1]):
        # A missing object is made (e.g. "response.restitution" turns the response on); a
        # missing list cannot be indexed into.
        create = not (parts[depth + 1].lstrip("-").isdigit() or parts[depth + 1] == "*")
        targets = [child for t in targets for child in _children(t, part, key, create)]
    last = parts[-1]
    for t in targets:
        if isinstance(t, list):
            t[_index(t, last, key)] = copy.deepcopy(value)
        else:
            t[last] = copy.deepcopy(value)


def _children(node, part, key, create):
    if isinstance(node, list):
        if part == "*":
            return list(node)
        return [node[_index(node, part, key)]]
    if not isinstance(node, dict):
        raise ValueError(f"vary key {key!r}: {part!r} is inside a value, not an object")
    if part not in node:
        if not create:
            raise ValueError(f"vary key {key!r}: no {part!r} in the scene to index into (set "
                             f"the whole value instead)")
        node[part] = {}
    return [node[part]]


def _index(items, part, key):
    """A list element by index, or a body by its name."""
    if part.lstrip("-").isdigit():
        i = int(part)
        if not -len(items) <= i < len(items):
            raise ValueError(f"vary key {key!r}: index {i} is out of range ({len(items)} items)")
        return i
    names = [item.get("name") if isinstance(item, dict) else None for item in items]
    if part in names:
        return names.index(part)
    raise ValueError(f"vary key {key!r}: {part!r} is neither an index nor a body name "
                     f"(bodies: {', '.join(str(n) for n in names)})")


def _perturb(scene, seed, size):
    if seed is None or size is None:
        raise ValueError("a perturbation needs both seed and perturb (the largest offset, m)")
    if not float(size) >= 0.0:
        raise ValueError(f"perturb must be 0 or more (m), got {size!r}")
    rng = np.random.default_rng(int(seed))
    for body in scene.get("bodies", []):
        offset = rng.uniform(-float(size), float(size), 3)
        position = [float(p) for p in body.get("position", [0.0, 0.0, 0.0])]
        body["position"] = [p + float(o) for p, o in zip(position, offset)]

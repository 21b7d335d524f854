"""Tiny scenes for the study's tests, written as files: two cubes of tetrahedra that meet."""

import json
import itertools


def write_cube_model(prefix, cells=2, size=0.2):
    """A cube of side `size`, cells^3 cells of 6 tetrahedra each (Kuhn's split, every cell's
    tetrahedra around its main diagonal), centred on the origin: PREFIX.node and PREFIX.ele."""
    n = cells + 1
    h = size / cells

    def node(i, j, k):
        return (i * n + j) * n + k

    nodes = [(i * h - size / 2, j * h - size / 2, k * h - size / 2)
             for i, j, k in itertools.product(range(n), repeat=3)]
    tets = []
    for i, j, k in itertools.product(range(cells), repeat=3):
        corner = [node(i + (c >> 2 & 1), j + (c >> 1 & 1), k + (c & 1)) for c in range(8)]
        for path in itertools.permutations(range(3)):  # 0 -> 7 along x, y, z in each order
            bits, chain = 0, [corner[0]]
            for axis in path:
                bits |= 4 >> axis
                chain.append(corner[bits])
            a, b, c, d = (nodes[v] for v in chain)
            if _volume6(a, b, c, d) < 0:  # every tetrahedron (b-a) x (c-a) . (d-a) > 0
                chain[2], chain[3] = chain[3], chain[2]
            tets.append(chain)
    with open(str(prefix) + ".node", "w") as f:
        f.write(f"{len(nodes)} 3 0 0\n")
        f.writelines(f"{i} {x!r} {y!r} {z!r}\n" for i, (x, y, z) in enumerate(nodes))
    with open(str(prefix) + ".ele", "w") as f:
        f.write(f"{len(tets)} 4 0\n")
        f.writelines(f"{i} {a} {b} {c} {d}\n" for i, (a, b, c, d) in enumerate(tets))


def _volume6(a, b, c, d):
    u = [b[i] - a[i] for i in range(3)]
    v = [c[i] - a[i] for i in range(3)]
    w = [d[i] - a[i] for i in range(3)]
    cross = (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0])
    return sum(cross[i] * w[i] for i in range(3))


def write_two_cubes(folder, frames=20, response=False, model="cube"):
    """folder/two_cubes.json: two cubes 0.3 m apart along x closing at 2 m/s, no gravity; the
    model `model` (a TetGen prefix written here when "cube"). Returns the scene's path."""
    if model == "cube":
        write_cube_model(folder / "cube")
    material = {"density": 1000, "stiffness": 10000, "damping": 0.0002}
    scene = {
        "settings": {"dt": 1 / 60, "substeps": 4, "gravity": [0, 0, 0], "frames": frames},
        "collision": {"broadphase": "bvh"},
        "bodies": [
            {"name": "left", "model": model, "position": [-0.25, 0, 0],
             "velocity": [1, 0, 0], "material": dict(material)},
            {"name": "right", "model": model, "position": [0.25, 0.05, 0],
             "velocity": [-1, 0, 0], "material": dict(material)},
        ],
    }
    if response:
        scene["response"] = {}
    path = folder / "two_cubes.json"
    path.write_text(json.dumps(scene, indent=1))
    return path

#!/usr/bin/env python3
"""Writes assets/models/surfaces/plate.obj: the closed box surface of scenes/fold.json's plate,
1.6 x 0.06 x 0.4 m on a regular 0.04 m grid (two rows through the thickness), triangles
counter-clockwise seen from outside. Then tetrahedralize it, keeping the surface:

    scripts/make_plate.py
    build/release/apps/deformcd/deformcd tetra assets/models/surfaces/plate.obj \
        -o assets/models/plate --preserve-surface --quality 1.5
"""
import pathlib

LENGTH, THICKNESS, DEPTH, GRID = 1.6, 0.06, 0.4, 0.04
NX, NY, NZ = round(LENGTH / GRID), 2, round(DEPTH / GRID)


def main():
    index = {}
    vertices = []

    def vertex(i, j, k):
        if (i, j, k) not in index:
            index[(i, j, k)] = len(vertices)
            vertices.append((-LENGTH / 2 + LENGTH * i / NX, THICKNESS * j / NY,
                             -DEPTH / 2 + DEPTH * k / NZ))
        return index[(i, j, k)]

    faces = []

    def quad(a, b, c, d):  # counter-clockwise seen from outside
        faces.append((a, b, c))
        faces.append((a, c, d))

    for i in range(NX):
        for k in range(NZ):
            quad(vertex(i, NY, k), vertex(i, NY, k + 1), vertex(i + 1, NY, k + 1), vertex(i + 1, NY, k))
            quad(vertex(i, 0, k), vertex(i + 1, 0, k), vertex(i + 1, 0, k + 1), vertex(i, 0, k + 1))
    for i in range(NX):
        for j in range(NY):
            quad(vertex(i, j, 0), vertex(i, j + 1, 0), vertex(i + 1, j + 1, 0), vertex(i + 1, j, 0))
            quad(vertex(i, j, NZ), vertex(i + 1, j, NZ), vertex(i + 1, j + 1, NZ), vertex(i, j + 1, NZ))
    for k in range(NZ):
        for j in range(NY):
            quad(vertex(0, j, k), vertex(0, j, k + 1), vertex(0, j + 1, k + 1), vertex(0, j + 1, k))
            quad(vertex(NX, j, k), vertex(NX, j + 1, k), vertex(NX, j + 1, k + 1), vertex(NX, j, k + 1))

    out = pathlib.Path(__file__).resolve().parent.parent / "assets/models/surfaces/plate.obj"
    with open(out, "w") as f:
        f.write("# plate: %.2f x %.2f x %.2f m box, %.2f m grid\n" % (LENGTH, THICKNESS, DEPTH, GRID))
        for v in vertices:
            f.write("v %.6f %.6f %.6f\n" % v)
        for a, b, c in faces:
            f.write("f %d %d %d\n" % (a + 1, b + 1, c + 1))
    print("%s: %d vertices, %d triangles" % (out, len(vertices), len(faces)))


if __name__ == "__main__":
    main()

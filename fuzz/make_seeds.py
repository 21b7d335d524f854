#!/usr/bin/env python3
"""Writes the fuzz targets' seed corpora, fuzz/corpus/<target>/, from tests/data/io and small
pieces of the shipped assets (the first faces or tetrahedra of a real model, renumbered), in
every variant the readers accept: OFF with colours, normals and counts on the header line; OBJ
with v/vt/vn references, groups and negative indices; STL ASCII and binary; PLY ASCII, binary
little and big endian with several property types; TetGen 0- and 1-based, with attributes,
markers and .face; the shipped scenes. Deterministic: running it again rewrites the same bytes.
Usage: fuzz/make_seeds.py   (from anywhere)
"""
import pathlib
import shutil
import struct

ROOT = pathlib.Path(__file__).resolve().parent.parent
DATA = ROOT / "tests" / "data" / "io"
MODELS = ROOT / "assets" / "models"
OUT = ROOT / "fuzz" / "corpus"


def read_off(path):
    tokens = [l.split("#")[0].split() for l in path.read_text().splitlines()]
    tokens = [t for t in tokens if t]
    nv, nf = int(tokens[1][0]), int(tokens[1][1])
    verts = [tuple(t[:3]) for t in tokens[2:2 + nv]]  # keep the file's decimal text
    faces = [tuple(int(i) for i in t[1:1 + int(t[0])]) for t in tokens[2 + nv:2 + nv + nf]]
    return verts, faces


def sub_surface(verts, faces, count):
    """The first `count` faces with the vertices they use, renumbered in order of first use."""
    index, out_v, out_f = {}, [], []
    for f in faces[:count]:
        for v in f:
            if v not in index:
                index[v] = len(out_v)
                out_v.append(verts[v])
        out_f.append(tuple(index[v] for v in f))
    return out_v, out_f


def off_text(verts, faces, header="OFF", counts_on_header=False, extra=""):
    lines = [f"{header} {len(verts)} {len(faces)} 0" if counts_on_header else header]
    if not counts_on_header:
        lines.append(f"{len(verts)} {len(faces)} 0")
    lines += [" ".join(v) + extra for v in verts]
    lines += [f"{len(f)} " + " ".join(map(str, f)) for f in faces]
    return "\n".join(lines) + "\n"


def stl_ascii(verts, faces):
    out = ["solid piece"]
    for f in faces:
        out += ["  facet normal 0 0 1", "    outer loop"]
        out += [f"      vertex {' '.join(verts[v])}" for v in f]
        out += ["    endloop", "  endfacet"]
    return "\n".join(out + ["endsolid piece"]) + "\n"


def stl_binary(verts, faces):
    data = b"binary STL seed".ljust(80, b" ") + struct.pack("<I", len(faces))
    for f in faces:
        data += struct.pack("<3f", 0, 0, 1)
        for v in f:
            data += struct.pack("<3f", *map(float, verts[v]))
        data += b"\0\0"
    return data


def ply(verts, faces, encoding, coord="float", count="uchar", index="int"):
    header = ["ply", f"format {encoding} 1.0", "comment seed", f"element vertex {len(verts)}",
              f"property {coord} x", f"property {coord} y", f"property {coord} z",
              "property uchar red", f"element face {len(faces)}",
              f"property list {count} {index} vertex_indices", "end_header"]
    text = ("\n".join(header) + "\n").encode()
    if encoding == "ascii":
        body = [" ".join(v) + " 7" for v in verts]
        body += [f"{len(f)} " + " ".join(map(str, f)) for f in faces]
        return text + ("\n".join(body) + "\n").encode()
    e = "<" if encoding == "binary_little_endian" else ">"
    fmt = {"float": "f", "double": "d", "uchar": "B", "ushort": "H", "int": "i", "uint": "I"}
    for v in verts:
        text += struct.pack(e + 3 * fmt[coord] + "B", *map(float, v), 7)
    for f in faces:
        text += struct.pack(e + fmt[count] + len(f) * fmt[index], len(f), *f)
    return text


def read_tetgen(prefix, ext):
    rows = [l.split("#")[0].split() for l in (MODELS / f"{prefix}.{ext}").read_text().splitlines()]
    return [r for r in rows if r][1:]


def sub_tetgen(prefix, count):
    nodes = {int(r[0]): r[1:4] for r in read_tetgen(prefix, "node")}
    tets = [tuple(int(i) for i in r[1:5]) for r in read_tetgen(prefix, "ele")[:count]]
    index, out_n = {}, []
    for t in tets:
        for n in t:
            if n not in index:
                index[n] = len(out_n)
                out_n.append(nodes[n])
    out_t = [tuple(index[n] for n in t) for t in tets]
    # The boundary of the piece: faces of one tetrahedron only.
    seen = {}
    for t in out_t:
        for f in ((t[1], t[2], t[3]), (t[0], t[3], t[2]), (t[0], t[1], t[3]), (t[0], t[2], t[1])):
            seen.setdefault(tuple(sorted(f)), []).append(f)
    faces = [fs[0] for fs in seen.values() if len(fs) == 1]
    return out_n, out_t, faces


def tetgen(nodes, tets, faces, base=0, attributes=False, markers=False):
    a = " 0.5" if attributes else ""
    m = " 1" if markers else ""
    node = [f"{len(nodes)} 3 {1 if attributes else 0} {1 if markers else 0}"]
    node += [f"{i + base} " + " ".join(p) + a + m for i, p in enumerate(nodes)]
    ele = [f"{len(tets)} 4 {1 if attributes else 0}"]
    ele += [f"{i + base} " + " ".join(str(n + base) for n in t) + a for i, t in enumerate(tets)]
    parts = ["\n".join(node) + "\n", "\n".join(ele) + "\n"]
    if faces is not None:
        face = [f"{len(faces)} {1 if markers else 0}"]
        face += [f"{i + base} " + " ".join(str(n + base) for n in f) + m
                 for i, f in enumerate(faces)]
        parts.append("\n".join(face) + "\n")
    return "\0".join(parts).encode()


def write(target, name, data):
    path = OUT / target / name
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_bytes(data.encode() if isinstance(data, str) else data)


def main():
    if OUT.exists():
        shutil.rmtree(OUT)
    cube_v, cube_f = read_off(DATA / "cube.off")
    bunny_v, bunny_f = sub_surface(*read_off(MODELS / "surfaces" / "bunny.off"), 40)
    lion_v, lion_f = sub_surface(*read_off(MODELS / "surfaces" / "lion.off"), 12)
    tri_v, tri_f = sub_surface(cube_v, [(0, 1, 2), (0, 2, 3), (4, 5, 6)], 3)

    write("off", "cube.off", (DATA / "cube.off").read_bytes())
    write("off", "bunny_piece.off", off_text(bunny_v, bunny_f))
    write("off", "lion_piece_header_counts.off", off_text(lion_v, lion_f, counts_on_header=True))
    write("off", "triangles_coff.off", off_text(tri_v, tri_f, "COFF", extra=" 255 0 0 255"))
    write("off", "triangles_noff.off", off_text(tri_v, tri_f, "NOFF", extra=" 0 0 1"))
    write("off", "triangles_stcnoff.off", off_text(tri_v, tri_f, "STCNOFF",
                                                    extra=" 0.5 0.5 1 0 0 0 0 1"))

    write("obj", "cube.obj", (DATA / "cube.obj").read_bytes())
    plate = (MODELS / "surfaces" / "plate.obj").read_text().splitlines()
    write("obj", "plate_piece.obj", "\n".join(
        [l for l in plate if l.startswith("v ")][:60] +
        [l for l in plate if l.startswith("f ")][:20]) + "\n")
    obj = ["# bunny piece", "o piece", "mtllib none.mtl", "usemtl skin"]
    obj += ["v " + " ".join(v) for v in bunny_v[:30]] + ["vt 0 0", "vt 1 0", "vn 0 0 1", "g a"]
    obj += ["f " + " ".join(f"{i + 1}/1/1" for i in f) for f in bunny_f if max(f) < 30][:10]
    obj += ["g b", "s off", "f -1 -2 -3", "f 1//1 2//1 3//1 4//1"]
    write("obj", "bunny_piece_refs.obj", "\n".join(obj) + "\n")

    write("stl", "octahedron_ascii.stl", (DATA / "octahedron.stl").read_bytes())
    oct_v, oct_f = [("1", "0", "0"), ("0", "1", "0"), ("0", "0", "1"), ("-1", "0", "0")], \
        [(0, 1, 2), (1, 3, 2)]
    write("stl", "two_binary.stl", stl_binary(oct_v, oct_f))
    write("stl", "bunny_piece_binary.stl", stl_binary(bunny_v, bunny_f[:20]))
    write("stl", "lion_piece_ascii.stl", stl_ascii(lion_v, lion_f))
    write("stl", "binary_with_solid_header.stl",
          b"solid but binary".ljust(80) + stl_binary(oct_v, oct_f)[80:])

    write("ply", "cube.ply", (DATA / "cube.ply").read_bytes())
    write("ply", "bunny_piece_ascii.ply", ply(bunny_v, bunny_f, "ascii"))
    write("ply", "bunny_piece_le.ply", ply(bunny_v, bunny_f[:20], "binary_little_endian"))
    write("ply", "bunny_piece_be.ply", ply(bunny_v, bunny_f[:20], "binary_big_endian"))
    write("ply", "lion_piece_le_double_uint.ply",
          ply(lion_v, lion_f, "binary_little_endian", "double", "uchar", "uint"))
    write("ply", "lion_piece_be_double_ushort.ply",
          ply(lion_v, lion_f, "binary_big_endian", "double", "ushort", "int"))

    cube = [(DATA / f"cube.{e}").read_text() for e in ("node", "ele", "face")]
    write("tetgen", "cube_1based_attributes_markers", "\0".join(cube))
    tet = [(DATA / f"tetrahedron.{e}").read_text() for e in ("node", "ele")]
    write("tetgen", "tetrahedron_no_face", "\0".join(tet))
    for model, count in (("plate", 30), ("bunny", 12)):
        n, t, f = sub_tetgen(model, count)
        write("tetgen", f"{model}_piece", tetgen(n, t, f))
        write("tetgen", f"{model}_piece_no_face", tetgen(n, t, None))
    n, t, f = sub_tetgen("dragon", 8)
    write("tetgen", "dragon_piece_1based_attributes_markers",
          tetgen(n, t, f, base=1, attributes=True, markers=True))

    for scene in ("hanging", "phase1", "phase2", "fold", "crossing16"):
        write("scene", f"{scene}.json", (ROOT / "scenes" / f"{scene}.json").read_bytes())
    # Regression inputs of findings (docs/reliability.md), replayed by every run.
    hanging = (ROOT / "scenes" / "hanging.json").read_text()
    write("scene", "finding_number_overflow.json",
          hanging.replace('"gravity": [0, -9.81, 0]', '"gravity": [0, -1e400, 0]'))


if __name__ == "__main__":
    main()

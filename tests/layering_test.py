#!/usr/bin/env python3
"""The source layout's rules (docs/architecture.md, "Layers"), checked over the tree.

1. One include style. In src/ and tests/, every #include "..." names a file by its path from a
   root: src/ for the library's private headers ("core/collision/bvh.h",
   "detector/backend_choice.h"), include/ for the public ones ("deformcd/detector.h"), and in
   tests/ also tests/ for the tests' helpers ("support/temp_dir.h", "gl/gl_test_context.h") and
   the repository for the tool's headers that tests compile ("apps/deformcd/progress.h"). The
   path must name exactly one file of those roots, and no other file beside the including one:
   a bare name ("bvh.h") or a path from the including file's folder does not count, even where
   the compiler finds it.
2. Dependencies point downward. A folder of src/ includes private headers only from itself and
   the folders below it (BELOW); src/core includes no public header of a layer above it
   (ABOVE_CORE), directly or through another public header.
3. No CMake include directory under src/ or tests/ offers a folder of src/ (such as src/core,
   through which "collision/..." would find src/core/collision) or the list's own folder: only
   src/, include/, tests/ and the repository.
4. The CPU and core code know no GL buffer bindings: src/core and src/cpu name no SSBO or
   binding point, not even in a comment (the binding table is the GL layer's: gpu::Binding,
   src/gpu/gl/collision_work_buffers.h, gl_proximity.h).

Usage: layering_test.py [REPOSITORY]   (default: this file's repository). Prints each violation
and exits 1 when there is one; CTest runs it as `layering` (tests/CMakeLists.txt).
"""

import pathlib
import re
import sys

# src/ folder -> the src/ folders whose headers it may include (itself included).
BELOW = {
    "core": {"core"},
    "io": {"core", "io"},
    "cpu": {"core", "cpu"},
    "gpu": {"core", "cpu", "gpu"},  # a widened proximity search runs on the host, on src/cpu's
    "scene": {"core", "io", "scene"},
    "tetgen": {"core", "io", "tetgen"},
    "detector": {"core", "cpu", "gpu", "detector"},
    "world": {"core", "cpu", "gpu", "detector", "world"},
    "render": {"core", "cpu", "gpu", "detector", "world", "render"},
}
# Public headers of the layers above src/core (files, or folders ending in "/").
ABOVE_CORE = (
    "deformcd/detector.h",
    "deformcd/intersection_census.h",
    "deformcd/world.h",
    "deformcd/world_intersections.h",
    "deformcd/scene.h",
    "deformcd/io.h",
    "deformcd/tetrahedralize.h",
    "deformcd/tetrahedralize_options.h",
    "deformcd/gl/",
    "deformcd/render/",
)
SOURCE_SUFFIXES = {".h", ".hpp", ".cpp", ".cc", ".c", ".inl"}
INCLUDE = re.compile(r'^\s*#\s*include\s*"([^"]+)"')
SHADER_SUFFIXES = (".glsl", ".comp", ".vert", ".frag")  # GLSL #includes in test strings


def includes(path):
    """(line number, name) of each #include "name" of a C++ file."""
    for number, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
        match = INCLUDE.match(line)
        if match and not match.group(1).endswith(SHADER_SUFFIXES):
            yield number, match.group(1)


def resolve(repo, source, name):
    """The file `name` names from `source` (a path relative to the repository), or a problem."""
    top = source.parts[0]
    roots = [("include", repo / "include"), ("src", repo / "src")]
    if top == "tests":
        roots.append(("tests", repo / "tests"))
        if name.startswith("apps/"):
            roots.append(("the repository", repo))
    found = [(label, root / name) for label, root in roots if (root / name).is_file()]
    if not found:
        where = ", ".join(label + "/" if label != "the repository" else label for label, _ in roots)
        if "/" not in name:
            return None, f'"{name}" is a bare name: write its path from {where}'
        return None, f'"{name}" is not a path from {where}'
    if len(found) > 1:
        return None, f'"{name}" names a file in {" and in ".join(l for l, _ in found)}'
    target = found[0][1].resolve()
    beside = (repo / source).parent / name
    if beside.is_file() and beside.resolve() != target:
        return None, f'"{name}" also names {beside.relative_to(repo)}, which the compiler finds first'
    if name.startswith("deformcd/") != (found[0][0] == "include"):
        return None, f'"{name}": public headers are "deformcd/...", and only they'
    return target.relative_to(repo), None


def public_closure(repo, name, seen):
    """`name` (a public header) and every public header it includes, transitively."""
    if name in seen:
        return seen
    seen.add(name)
    path = repo / "include" / name
    if path.is_file():
        for _, inner in includes(path):
            if inner.startswith("deformcd/"):
                public_closure(repo, inner, seen)
    return seen


def check_includes(repo, problems):
    sources = sorted(p for top in ("src", "tests") for p in (repo / top).rglob("*")
                     if p.suffix in SOURCE_SUFFIXES and p.is_file())
    for path in sources:
        source = path.relative_to(repo)
        folder = source.parts[1] if source.parts[0] == "src" else None
        for number, name in includes(path):
            where = f"{source}:{number}"
            target, problem = resolve(repo, source, name)
            if problem:
                problems.append(f"{where}: {problem}")
                continue
            if folder is None:
                continue
            if target.parts[0] == "src" and target.parts[1] not in BELOW.get(folder, {folder}):
                problems.append(f"{where}: src/{folder} includes {target}, a layer above it "
                                f"(src/{folder} may include {', '.join(sorted(BELOW[folder]))})")
            if folder == "core" and target.parts[0] == "include":
                for public in sorted(public_closure(repo, name, set())):
                    if public.startswith(ABOVE_CORE):
                        via = "" if public == name else f" (through {name})"
                        problems.append(f"{where}: src/core includes {public}{via}, the public "
                                        "header of a layer above it")


def check_include_directories(repo, problems):
    block = re.compile(r"target_include_directories\s*\(([^)]*)\)", re.S)
    for lists in sorted(p for top in ("src", "tests") for p in (repo / top).rglob("CMakeLists.txt")):
        text = lists.read_text(encoding="utf-8")
        for match in block.finditer(text):
            line = text.count("\n", 0, match.start()) + 1
            body = re.sub(r"#[^\n]*", "", match.group(1))
            for word in body.split():
                if re.search(r"CMAKE_CURRENT_(SOURCE|LIST)_DIR|PROJECT_SOURCE_DIR}/src/", word):
                    problems.append(f"{lists.relative_to(repo)}:{line}: include directory {word}: "
                                    "only src/, include/ and tests/ (then paths from them)")


def check_no_gl_bindings(repo, problems):
    mention = re.compile(r"\bSSBOs?\b|\bbinding points?\b|\bk\w+Binding\b|\bgpu::Binding\b", re.I)
    for top in ("src/core", "src/cpu"):
        for path in sorted(p for p in (repo / top).rglob("*") if p.suffix in SOURCE_SUFFIXES):
            for number, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
                if mention.search(line):
                    problems.append(f"{path.relative_to(repo)}:{number}: a GL buffer binding in "
                                    f"CPU code ({line.strip()}): say what the array holds")


def main(argv):
    repo = pathlib.Path(argv[1] if len(argv) > 1 else pathlib.Path(__file__).parent.parent).resolve()
    problems = []
    check_includes(repo, problems)
    check_include_directories(repo, problems)
    check_no_gl_bindings(repo, problems)
    for problem in problems:
        print(problem)
    if problems:
        print(f"{len(problems)} layering problem(s); the rules are at the top of "
              "tests/layering_test.py and in docs/architecture.md")
        return 1
    print("layering: every include a path from a root, every dependency downward")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))

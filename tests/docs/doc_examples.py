#!/usr/bin/env python3
"""The fenced code blocks of README.md and docs/*.md (not docs/notes/, a log nobody has to read),
and the rules that keep them true. Every block carries a label after its opening fence:

  cpp         a complete program (with main). CMake compiles each against the libraries and
              CTest runs it from the repository root (tests/docs/CMakeLists.txt); exit 0 passes.
  python      run with /usr/bin/python3 and the build tree's module, in a scratch folder that
              links the repository as `sh run` does (relative paths work; outputs land there).
  sh          checked, not run (builds, the main job, benchmarks of minutes): each command must
              name an existing script of the repository, a deformcd command with options that its
              --help lists, a program under build/PRESET/ that the named folder's CMakeLists.txt
              builds, or one of KNOWN_TOOLS; and every scenes/, assets/, scripts/, examples/ path
              in it must exist (a TetGen prefix: its .node file).
  sh run      checked as above, and run with bash (-e -u -o pipefail) in a scratch folder that
              links every top-level entry of the repository (scenes/, assets/...), with the
              build's deformcd first on PATH; outputs land in the scratch folder. For short
              commands on shipped small inputs: running is opt-in, so that no page runs a
              minutes-long job in the tests by accident.
  json        data; docs/scenes.md's are read as scenes by tests/docs/scene_reference_test.cpp.
  text, cmake not examples: command output, messages, diagrams, build snippets (tests/package
              builds a project against the installed package).

A block with no label or another label fails the `lint` check, so no example goes unchecked;
`lint` also checks that README.md links every page of docs/ (not the notes).

Usage:
  doc_examples.py extract-cpp SOURCE_DIR OUT_DIR   (at configure time: OUT_DIR/*.cpp and
                                                    OUT_DIR/examples.cmake)
  doc_examples.py lint SOURCE_DIR OUT_DIR          (labels; the C++ blocks CMake compiled are
                                                    still those of the pages)
  doc_examples.py run-python SOURCE_DIR PYTHONPATH
  doc_examples.py run-sh SOURCE_DIR DEFORMCD
  doc_examples.py check-sh SOURCE_DIR DEFORMCD
"""

import contextlib
import dataclasses
import os
import pathlib
import re
import shlex
import subprocess
import sys
import tempfile

LABELS = {"cpp", "python", "sh", "json", "text", "cmake"}
KNOWN_TOOLS = {"cmake", "ctest", "git", "apt-get", "sudo", "xvfb-run", "perf", "taskset", "head",
               "cat", "ls", "mkdir", "cd", ".", "source"}
PYTHONS = {"python3", "/usr/bin/python3", "python"}  # python: a venv's
REPO_PATH_PREFIXES = ("scenes/", "assets/", "scripts/", "examples/")
TIMEOUT_S = 600


@dataclasses.dataclass
class Block:
    page: str  # relative to the repository, e.g. docs/detector.md
    line: int  # of the opening fence, 1-based
    label: str
    flags: list
    text: str

    @property
    def where(self):
        return f"{self.page}:{self.line}"

    @property
    def slug(self):
        page = re.sub(r"[^A-Za-z0-9]+", "_", self.page.removesuffix(".md")).strip("_").lower()
        return f"{page}_{self.line}"


def pages(source):
    """README.md and every docs/ page but the notes, in a fixed order."""
    source = pathlib.Path(source)
    found = [source / "README.md"]
    found += sorted(p for p in (source / "docs").rglob("*.md")
                    if "notes" not in p.relative_to(source / "docs").parts)
    return [p for p in found if p.exists()]


def blocks(source):
    out = []
    for page in pages(source):
        rel = page.relative_to(source).as_posix()
        lines = page.read_text(encoding="utf-8").split("\n")
        i = 0
        while i < len(lines):
            m = re.match(r"^(\s*)```(.*)$", lines[i])
            if not m:
                i += 1
                continue
            indent, info = m.group(1), m.group(2).strip()
            start = i
            body = []
            i += 1
            while i < len(lines) and not re.match(r"^\s*```\s*$", lines[i]):
                body.append(lines[i][len(indent):] if lines[i].startswith(indent) else lines[i])
                i += 1
            words = info.split()
            out.append(Block(rel, start + 1, words[0] if words else "", words[1:],
                             "\n".join(body) + "\n"))
            i += 1
    return out


def cpp_requirements(text):
    """What a C++ example needs beyond the libraries every build has ("gl" first: a build
    without GL skips the example before looking for anything else)."""
    needs = []
    if "<GLFW/" in text or "<deformcd/gl/" in text or "<deformcd/render/" in text \
            or "BackendKind::kGl" in text:
        needs.append("gl")
    if "<GLFW/" in text:
        needs.append("glfw")
    if "<deformcd/tetrahedralize.h>" in text:
        needs.append("tetgen")
    return needs


def write_if_changed(path, text):
    if not path.exists() or path.read_text(encoding="utf-8") != text:
        path.write_text(text, encoding="utf-8")


def extract_cpp(source, out_dir):
    out_dir = pathlib.Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    calls = []
    manifest = []
    for b in blocks(source):
        if b.label != "cpp":
            continue
        file = out_dir / f"{b.slug}.cpp"
        write_if_changed(file, f"// Extracted from {b.where} by tests/docs/doc_examples.py: edit "
                               f"the page, not this file.\n" + b.text)
        calls.append(f"deformcd_doc_example({b.slug} \"{b.where}\" \"{file.as_posix()}\" "
                     f"\"{';'.join(cpp_requirements(b.text))}\")")
        manifest.append(b.where)
    depends = "\n".join(f"  \"{p.as_posix()}\"" for p in pages(source))
    write_if_changed(out_dir / "examples.cmake",
                     "# Generated by tests/docs/doc_examples.py extract-cpp.\n"
                     f"set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS\n{depends})\n"
                     + "\n".join(calls) + "\n")
    write_if_changed(out_dir / "manifest.txt", "\n".join(manifest) + "\n")


def lint(source, out_dir):
    problems = []
    for b in blocks(source):
        if b.label not in LABELS:
            what = f"labelled '{b.label}'" if b.label else "without a label"
            problems.append(f"{b.where}: a fenced block {what}: label it "
                            "cpp, python, sh (or sh run), json, text or cmake "
                            "(the rules are at the top of tests/docs/doc_examples.py)")
        elif b.flags and not (b.label == "sh" and b.flags == ["run"]):
            problems.append(f"{b.where}: unknown flags {' '.join(b.flags)} after '{b.label}' "
                            "(only 'sh run' takes one)")
        if b.label == "cpp" and "int main(" not in b.text:
            problems.append(f"{b.where}: a cpp block must be a complete program with int main()")
    readme = pathlib.Path(source, "README.md").read_text(encoding="utf-8")
    for page in sorted(pathlib.Path(source, "docs").glob("*.md")):
        link = f"(docs/{page.name})"
        if link not in readme:
            problems.append(f"README.md does not link docs/{page.name}: add {link} to its "
                            "table of pages")
    compiled = pathlib.Path(out_dir, "manifest.txt").read_text(encoding="utf-8").split()
    now = [b.where for b in blocks(source) if b.label == "cpp"]
    if compiled != now:
        problems.append("the C++ blocks compiled at configure time (" + ", ".join(compiled) +
                        ") are not the pages' C++ blocks now (" + ", ".join(now) +
                        "): re-run cmake (a new page is not watched until then)")
    return problems


@contextlib.contextmanager
def scratch_folder(source):
    """A temporary folder linking every top-level folder of the repository but .git and build, so
    that an example's relative paths (scenes/, assets/) work and its outputs land outside the
    source tree. Folders only: a link to a top-level file would be written through (outputs
    follow symlinks), as a link to a stray impact.csv was by the study example."""
    with tempfile.TemporaryDirectory(prefix="deformcd_docs_") as scratch:
        for entry in pathlib.Path(source).iterdir():
            if entry.is_dir() and entry.name not in (".git", "build"):
                os.symlink(entry, pathlib.Path(scratch, entry.name))
        yield scratch


def run_python(source, pythonpath):
    problems = []
    env = dict(os.environ, PYTHONPATH=pythonpath, MPLBACKEND="Agg", PYTHONDONTWRITEBYTECODE="1")
    for b in blocks(source):
        if b.label != "python":
            continue
        print(f"== {b.where}", flush=True)
        with scratch_folder(source) as scratch:
            r = subprocess.run(["/usr/bin/python3", "-c", b.text], cwd=scratch, env=env,
                               capture_output=True, text=True, timeout=TIMEOUT_S, check=False)
        print(r.stdout + r.stderr, flush=True)
        if r.returncode != 0:
            problems.append(f"{b.where}: the Python example exited with {r.returncode}:\n"
                            f"{r.stderr.strip()}")
    return problems


def deformcd_commands(deformcd):
    """The commands `deformcd --help` lists (a build without GL has no render or view)."""
    text = subprocess.run([deformcd, "--help"], capture_output=True, text=True,
                          check=False).stdout
    return set(re.findall(r"^\s{2}([a-z][a-z-]*)\s", text, re.MULTILINE))


def help_options(deformcd, command):
    text = subprocess.run([deformcd, command, "--help"], capture_output=True, text=True,
                          check=False).stdout
    options = set()
    for m in re.finditer(r"^\s+(?:(-\w),)?(--[a-z][a-z-]*)", text, re.MULTILINE):
        options.add(m.group(2))
        if m.group(1):
            options.add(m.group(1))
    return options


def commands_of(text):
    """The commands of a shell block: continuation lines joined, comments dropped."""
    joined = re.sub(r"\\\n\s*", " ", text)
    out = []
    for line in joined.split("\n"):
        try:
            words = shlex.split(line, comments=True)
        except ValueError as e:
            out.append(("", [f"<unparsable: {e}>"]))
            continue
        if words:
            out.append((line.strip(), words))
    return out


def deformcd_used(block, commands):
    """The deformcd commands a block runs that this build does not have (none: run it)."""
    used = set(re.findall(r"(?:^|[\s/])deformcd\s+([a-z][a-z-]*)", block.text))
    return sorted(used - commands)


def run_sh(source, deformcd):
    problems = []
    commands = deformcd_commands(deformcd)
    env = dict(os.environ, PATH=str(pathlib.Path(deformcd).resolve().parent) + os.pathsep +
               os.environ.get("PATH", ""))
    for b in blocks(source):
        if b.label != "sh" or b.flags != ["run"]:
            continue
        missing = deformcd_used(b, commands)
        if missing:
            print(f"== {b.where}: not run, this build has no deformcd {', '.join(missing)}")
            continue
        print(f"== {b.where}", flush=True)
        with scratch_folder(source) as scratch:
            r = subprocess.run(["bash", "-euo", "pipefail", "-c", b.text], cwd=scratch, env=env,
                               capture_output=True, text=True, timeout=TIMEOUT_S, check=False)
        print(r.stdout + r.stderr, flush=True)
        if r.returncode != 0:
            problems.append(f"{b.where}: the shell example exited with {r.returncode}:\n"
                            f"{(r.stdout + r.stderr).strip()[-2000:]}")
    return problems


def check_command(source, where, line, words, deformcd, commands, help_cache):
    problems = []
    while words and (re.match(r"^[A-Z_][A-Z0-9_]*=", words[0]) or words[0] == "sudo"):
        words = words[1:]
    if not words:
        return problems
    program, args = words[0], words[1:]
    for arg in args:
        if arg.startswith(REPO_PATH_PREFIXES) and not pathlib.Path(source, arg).exists() \
                and not pathlib.Path(source, arg + ".node").exists():
            problems.append(f"{where}: `{line}` names {arg}, which does not exist")
    build = re.match(r"^build/[^/]+/(.+)/([^/]+)$", program)
    if program == "deformcd" or program.endswith("/apps/deformcd/deformcd"):
        if not args or args[0].startswith("-"):
            return problems
        command = args[0]
        if command not in commands:
            print(f"{where}: `deformcd {command}` not checked: this build does not have it")
            return problems
        if command not in help_cache:
            help_cache[command] = help_options(deformcd, command)
        for arg in args[1:]:
            option = arg.split("=", 1)[0]
            if re.match(r"^--?[A-Za-z]", option) and option not in help_cache[command]:
                problems.append(f"{where}: `{line}` uses {option}, which `deformcd {command} "
                                f"--help` does not list")
    elif build:
        folder, name = build.group(1), build.group(2)
        lists = pathlib.Path(source, folder, "CMakeLists.txt")
        if not lists.exists() or not re.search(rf"\b{re.escape(name)}\b", lists.read_text()):
            problems.append(f"{where}: `{line}` runs {program}, but {folder}/CMakeLists.txt "
                            f"builds no {name}")
    elif "/" in program and program not in PYTHONS:
        if not pathlib.Path(source, program).exists():
            problems.append(f"{where}: `{line}` runs {program}, which does not exist")
    elif program in PYTHONS:
        # python3 SCRIPT must name an existing script; python3 -m MODULE is not checked (the
        # module may be the build's, on PYTHONPATH), nor python3 -c CODE.
        script = next((a for a in args if not a.startswith("-")), None)
        if script and "-m" not in args and "-c" not in args and not pathlib.Path(source, script).exists():
            problems.append(f"{where}: `{line}` runs {script}, which does not exist")
    elif program not in KNOWN_TOOLS:
        problems.append(f"{where}: `{line}`: {program} is neither a script of the repository, a "
                        f"deformcd command nor a known tool (KNOWN_TOOLS in "
                        f"tests/docs/doc_examples.py)")
    return problems


def check_sh(source, deformcd):
    problems = []
    commands = deformcd_commands(deformcd)
    help_cache = {}
    for b in blocks(source):
        if b.label != "sh":
            continue
        for line, words in commands_of(b.text):
            problems += check_command(source, b.where, line, words, deformcd, commands,
                                      help_cache)
    return problems


def main(argv):
    if len(argv) != 4:
        print(__doc__)
        return 2
    mode, source, arg = argv[1], pathlib.Path(argv[2]).resolve(), argv[3]
    if mode == "extract-cpp":
        extract_cpp(source, arg)
        return 0
    problems = {"lint": lint, "run-python": run_python, "run-sh": run_sh,
                "check-sh": check_sh}[mode](source, arg)
    for p in problems:
        print(f"FAIL {p}")
    print(f"{mode}: {len(problems)} problem(s)")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))

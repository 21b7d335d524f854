#!/usr/bin/env python3
"""clang-tidy (.clang-tidy) over source files with a build's compile commands, JOBS at a time,
skipping the files that passed before with exactly the same inputs.

Usage: scripts/tidy.py [-p BUILD_DIR] [FILE...]
  (default: -p build/release, the files of `git ls-files 'src/*.cpp'` that the build compiles;
  the others, such as the build without GL's backend_choice_none.cpp, are named and skipped)

A file's key is the SHA-256 of clang-tidy's version, every .clang-tidy of the repository, the
clang-tidy arguments below, the file's compile command, and the file as clang preprocesses it
with that command (every header it includes, with its path and contents, after the macros).
clang-tidy sees nothing else, so a file whose key passed before passes again. A file that
passes leaves its key in the cache ($DEFORMCD_TIDY_CACHE, default ~/.cache/deformcd-tidy;
DEFORMCD_TIDY_CACHE=off: no cache); a file with a finding, or one clang cannot preprocess,
leaves nothing and is checked every time. Jobs: $DEFORMCD_JOBS (default 2).
"""

import argparse
import concurrent.futures
import hashlib
import json
import os
import pathlib
import shlex
import subprocess
import sys

CACHE_FORMAT = "1"  # bump when the key's recipe changes
TIDY_ARGS = ["--quiet", "--extra-arg=-Wno-unknown-warning-option"]
NOISE = ("warnings generated", "warning generated")  # clang-tidy's count of what it filtered


def compile_arguments(entry):
    if "arguments" in entry:
        return list(entry["arguments"])
    return shlex.split(entry["command"])


def preprocess_command(entry):
    """The compile command with clang++ as the compiler, writing the preprocessed file to stdout."""
    args = compile_arguments(entry)
    out = ["clang++"]
    skip = False
    for a in args[1:]:
        if skip:
            skip = False
            continue
        if a == "-o":
            skip = True
            continue
        if a == "-c" or a.startswith("-o"):
            continue
        out.append(a)
    # -CC keeps the comments (NOLINT and its kin steer clang-tidy), macros' included.
    return out + ["-Wno-unknown-warning-option", "-E", "-CC"]


def key_of(file_entries, common):
    """The file's cache key, or None when clang cannot preprocess it (then it is never cached).
    A file compiled twice (two entries) is checked by clang-tidy with each command: both count."""
    h = hashlib.sha256(common)
    for entry in file_entries:
        result = subprocess.run(preprocess_command(entry), cwd=entry["directory"],
                                stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, check=False)
        if result.returncode != 0:
            return None
        h.update(json.dumps([entry["directory"], entry["file"], compile_arguments(entry)]).encode())
        h.update(hashlib.sha256(result.stdout).digest())
    return h.hexdigest()


def main():
    root = pathlib.Path(__file__).resolve().parent.parent
    os.chdir(root)
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("-p", dest="build", default="build/release")
    parser.add_argument("files", nargs="*")
    opts = parser.parse_args()
    build = (root / opts.build).resolve()
    entries = {}
    for e in json.loads((build / "compile_commands.json").read_text()):
        entries.setdefault(str((pathlib.Path(e["directory"]) / e["file"]).resolve()), []).append(e)
    files = opts.files
    if not files:
        # Every library source this build compiles; the others are another configuration's
        # (src/detector/backend_choice_none.cpp is the build without GL's): named, not checked.
        tracked = subprocess.run(["git", "ls-files", "src/*.cpp"], check=True,
                                 stdout=subprocess.PIPE, text=True).stdout.split()
        files = [f for f in tracked if str((root / f).resolve()) in entries]
        for f in tracked:
            if f not in files:
                print(f"{f}: not compiled in {build.name}, not checked")

    cache_setting = os.environ.get("DEFORMCD_TIDY_CACHE", "")
    cache = None
    if cache_setting != "off":
        cache = pathlib.Path(cache_setting or pathlib.Path.home() / ".cache" / "deformcd-tidy")
        cache.mkdir(parents=True, exist_ok=True)
    common = hashlib.sha256()
    common.update(CACHE_FORMAT.encode())
    for tool in ("clang-tidy", "clang++"):
        version = subprocess.run([tool, "--version"], check=True, stdout=subprocess.PIPE)
        common.update(version.stdout)
    configs = subprocess.run(["git", "ls-files", "-co", "--exclude-standard", ".clang-tidy",
                              "*/.clang-tidy"], check=True, stdout=subprocess.PIPE,
                             text=True).stdout.split()
    for config in sorted(configs):
        common.update(config.encode() + b"\0" + (root / config).read_bytes())
    common.update(json.dumps(TIDY_ARGS).encode())
    common = common.digest()

    def check(path):
        """(path, passed, from_cache, output)"""
        file_entries = entries.get(str((root / path).resolve()))
        if not file_entries:
            return path, False, False, f"{path}: not in {build}/compile_commands.json\n"
        key = key_of(file_entries, common) if cache else None
        if key and (cache / key).exists():
            return path, True, True, ""
        result = subprocess.run(["clang-tidy", "-p", str(build), *TIDY_ARGS, str(root / path)],
                                stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                                check=False)
        output = result.stdout + "".join(
            line for line in result.stderr.splitlines(keepends=True)
            if not any(n in line for n in NOISE))
        passed = result.returncode == 0
        if passed and key:
            (cache / key).touch()
        return path, passed, False, output

    jobs = int(os.environ.get("DEFORMCD_JOBS", "2"))
    failed = cached = 0
    with concurrent.futures.ThreadPoolExecutor(max_workers=jobs) as pool:
        for path, passed, from_cache, output in pool.map(check, files):
            sys.stdout.write(output)
            sys.stdout.flush()
            failed += 0 if passed else 1
            cached += 1 if from_cache else 0
    where = f"cache {cache}" if cache else "no cache"
    print(f"clang-tidy: {len(files)} files, {cached} unchanged since they passed ({where}), "
          f"{len(files) - cached} checked, {failed} with findings")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())

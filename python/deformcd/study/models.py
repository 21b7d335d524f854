"""The models of a study's scenes, made ready for the workers on the client, once per study.

Surface models (.off .obj .stl .ply) are tetrahedralized here, not on the workers: the module
reads TetGen models only, since TetGen (AGPL-3) is linked into the `deformcd` tool and kept out
of the module. Each distinct (file content, meshing) is meshed once by `deformcd tetra`, in a
separate process, into a cache folder named by the hash of both; later studies reuse it.

Then each body's model is either shipped (its TetGen files' bytes go to every worker once, and
the task writes them into its own folder: no shared file system needed) or named by its absolute
path (models="shared": every worker must see the same path, e.g. an NFS home).
"""

import hashlib
import json
import os
import pathlib
import shutil
import subprocess
import tempfile

SURFACE_SUFFIXES = (".off", ".obj", ".stl", ".ply")
TETGEN_SUFFIXES = (".node", ".ele", ".face")
# What a scene's surface model gets without a `meshing` object (scene.h, default_scene_meshing).
DEFAULT_MESHING = {"quality": 2.0, "preserve_surface": True}


def default_cache_dir():
    """$XDG_CACHE_HOME/deformcd/tetra, else ~/.cache/deformcd/tetra."""
    base = os.environ.get("XDG_CACHE_HOME") or pathlib.Path.home() / ".cache"
    return pathlib.Path(base) / "deformcd" / "tetra"


def find_cli(cli=None):
    """The `deformcd` tool: `cli`, else $DEFORMCD_CLI, else `deformcd` on PATH; None if none."""
    for candidate in (cli, os.environ.get("DEFORMCD_CLI"), shutil.which("deformcd")):
        if candidate and os.access(candidate, os.X_OK):
            return str(candidate)
    if cli:
        raise FileNotFoundError(f"cli={cli!r} is not an executable (the deformcd tool)")
    return None


class ModelPreparer:
    """Rewrites scenes' model paths for the workers: surface models meshed once (cached by
    content and meshing), TetGen models shipped or named by absolute path."""

    def __init__(self, scene_dir, models="ship", cli=None, cache_dir=None, log=print):
        if models not in ("ship", "shared"):
            raise ValueError(f"models must be 'ship' or 'shared', got {models!r}")
        self.scene_dir = pathlib.Path(scene_dir)
        self.mode = models
        self.cli = cli
        self.cache_dir = pathlib.Path(cache_dir) if cache_dir else default_cache_dir()
        self.log = log
        self.bundle = {}  # shipped models: key -> {suffix: bytes}
        self.meshed = {}  # (surface path, meshing) -> cached prefix, this study's
        self._shipped = {}  # absolute prefix -> bundle key

    def prepare(self, scene):
        """The scene (a dict, changed in place and returned) with every body's model made a
        TetGen model the workers can read: "models/KEY" (shipped) or an absolute prefix."""
        for i, body in enumerate(scene.get("bodies", [])):
            if "model" not in body:
                continue  # the scene reader names the missing key, on the worker
            path = self.scene_dir / body["model"]
            if path.suffix.lower() in SURFACE_SUFFIXES:
                meshing = {**DEFAULT_MESHING, **body.pop("meshing", {})}
                path = self._meshed(path, meshing, f"bodies/{i}")
            body["model"] = self._tetgen_model(path.resolve(), f"bodies/{i}")
        return scene

    def _meshed(self, surface, meshing, where):
        if not surface.is_file():
            raise FileNotFoundError(f"{where}/model: no such surface model: {surface}")
        key = (str(surface.resolve()), json.dumps(meshing, sort_keys=True))
        if key in self.meshed:
            return self.meshed[key]
        digest = hashlib.sha256(surface.read_bytes())
        digest.update(key[1].encode())
        folder = self.cache_dir / digest.hexdigest()[:32]
        prefix = folder / surface.stem
        if (folder / "done").is_file():
            self.log(f"study: {surface.name}: meshed before, {prefix}")
        else:
            self._run_tetra(surface, meshing, folder, where)
        self.meshed[key] = prefix
        return prefix

    def _run_tetra(self, surface, meshing, folder, where):
        cli = find_cli(self.cli)
        if cli is None:
            raise FileNotFoundError(
                f"{where}/model: {surface} is a surface model; the study meshes it with the "
                f"`deformcd` tool (`deformcd tetra`), which is neither on PATH nor named by "
                f"cli= / $DEFORMCD_CLI (build the `deformcd` target), or name a TetGen prefix "
                f"in the scene")
        self.cache_dir.mkdir(parents=True, exist_ok=True)
        # Meshed into a private folder, then renamed into place: a study running beside this
        # one sees the cache entry whole or not at all.
        work = pathlib.Path(tempfile.mkdtemp(prefix=".meshing-", dir=self.cache_dir))
        command = [cli, "tetra", str(surface), "-o", str(work / surface.stem)]
        if meshing.get("quality") is not None:
            command += ["--quality", repr(float(meshing["quality"]))]
        if meshing.get("max_volume") is not None:
            command += ["--max-volume", repr(float(meshing["max_volume"]))]
        if meshing.get("preserve_surface"):
            command.append("--preserve-surface")
        self.log(f"study: meshing {surface.name} once: {' '.join(command)}")
        done = subprocess.run(command, capture_output=True, text=True)
        if done.returncode != 0:
            shutil.rmtree(work, ignore_errors=True)
            raise RuntimeError(f"{where}/model: `{' '.join(command)}` failed "
                               f"(exit {done.returncode}): {done.stderr.strip()}")
        (work / "done").write_text(" ".join(command) + "\n")
        try:
            work.rename(folder)
        except OSError:  # another study got there first: its files are the same
            shutil.rmtree(work, ignore_errors=True)

    def _tetgen_model(self, prefix, where):
        if self.mode == "shared":
            return str(prefix)
        if str(prefix) not in self._shipped:
            files = {}
            for suffix in TETGEN_SUFFIXES:
                file = prefix.with_name(prefix.name + suffix)
                if file.is_file():
                    files[suffix] = file.read_bytes()
            if ".node" not in files:
                raise FileNotFoundError(f"{where}/model: no TetGen model {prefix}.node")
            digest = hashlib.sha256()
            for suffix in sorted(files):
                digest.update(suffix.encode() + files[suffix])
            key = digest.hexdigest()[:32]
            self.bundle[key] = files
            self._shipped[str(prefix)] = key
        return "models/" + self._shipped[str(prefix)]


def write_models(folder, bundle, scene):
    """Writes the shipped models the scene names ("models/KEY") into folder/models."""
    target = pathlib.Path(folder) / "models"
    target.mkdir(exist_ok=True)
    for body in scene.get("bodies", []):
        model = body.get("model", "")
        if model.startswith("models/"):
            key = model[len("models/"):]
            for suffix, data in bundle[key].items():
                (target / (key + suffix)).write_bytes(data)

"""The module from a virtual environment (issue 37): one made from the interpreter the module is
built for with --system-site-packages sees its NumPy and works; one without says why it cannot
work instead of importing and failing later on NumPy."""

import os
import subprocess

import pytest

import deformcd
from conftest import SOURCE_DIR


def make_venv(folder, system_site_packages):
    command = [deformcd.BUILT_FOR, "-m", "venv", "--without-pip", str(folder)]
    if system_site_packages:
        command.insert(3, "--system-site-packages")
    done = subprocess.run(command, capture_output=True, text=True, timeout=120)
    if done.returncode != 0:
        pytest.skip(f"no venv ({' '.join(command)}: {done.stderr.strip()}; python3-venv)")
    return folder / "bin" / "python"


def run_in(python, code):
    # The tests' environment: PYTHONPATH names the build tree's package (and under the
    # sanitizers LD_PRELOAD their runtimes); the venv decides which site-packages are seen.
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONHOME", "VIRTUAL_ENV")}
    return subprocess.run([str(python), "-c", code], capture_output=True, text=True, env=env,
                          timeout=120, cwd=SOURCE_DIR)


def test_venv_with_system_site_packages_runs_a_world(tmp_path):
    python = make_venv(tmp_path / "env", system_site_packages=True)
    done = run_in(python, "import sys, deformcd; w = deformcd.World.from_scene("
                          "'scenes/phase2.json', frames=2, backend='cpu'); w.step(2); "
                          "print(sys.prefix, w.positions(0).dtype, w.frame)")
    assert done.returncode == 0, done.stderr
    prefix, dtype, frame = done.stdout.split()
    assert prefix == str(tmp_path / "env") and dtype == "float32" and frame == "2"


def test_venv_without_system_site_packages_says_what_to_do(tmp_path):
    python = make_venv(tmp_path / "bare", system_site_packages=False)
    done = run_in(python, "import deformcd")
    assert done.returncode != 0
    assert "ImportError: deformcd was built for " + deformcd.BUILT_FOR in done.stderr
    assert "needs NumPy" in done.stderr and "--system-site-packages" in done.stderr

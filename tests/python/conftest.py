"""Shared by the deformcd Python tests: where the sources and the CLI are, and test meshes.

Run by CTest (python_tests), or alone:
    PYTHONPATH=build/<preset>/python /usr/bin/python3 -m pytest tests/python
DEFORMCD_CLI names the `deformcd` tool for the comparisons with it (skipped without it; CTest
sets it when the tool is built).
"""

import os
import pathlib
import sys

import numpy as np
import pytest

SOURCE_DIR = pathlib.Path(os.environ.get("DEFORMCD_SOURCE_DIR",
                                         pathlib.Path(__file__).resolve().parents[2]))
# The example's mesh generator is the tests' too (one icosphere in the tree).
sys.path.insert(0, str(SOURCE_DIR / "examples"))

from compare_broadphases import icosphere, sliding_pose  # noqa: E402


@pytest.fixture
def cli():
    """The deformcd command-line tool, or skip."""
    path = os.environ.get("DEFORMCD_CLI")
    if not path or not os.access(path, os.X_OK):
        pytest.skip("DEFORMCD_CLI does not name the deformcd tool (build the `deformcd` target)")
    return path


@pytest.fixture(scope="session")
def spheres():
    """Two icospheres (1,280 triangles each) and the moving one's rest pose: sphere 1 is placed
    by sliding_pose(rest1, frame, 30, V1) as in the example (frames 9-20 of 30 in contact)."""
    V0, F0 = icosphere(3, radius=1.0)
    rest1, F1 = icosphere(3, radius=0.7)
    return V0, F0, rest1, F1


@pytest.fixture(scope="session")
def separate_cluster(tmp_path_factory):
    """A Dask scheduler and two workers, each a process of its own on 127.0.0.1, shared by the
    study's tests (study_support.SeparateCluster); the study's tests that use it run last."""
    from study_support import SeparateCluster

    cluster = SeparateCluster(tmp_path_factory.mktemp("dask"))
    yield cluster
    cluster.stop()


def pose(rest, frame, frames=30):
    out = np.empty_like(rest)
    sliding_pose(rest, frame, frames, out)
    return out


def contact_rows(c):
    """(body_a, face_a, body_b, face_b) rows of a contacts() dict."""
    return np.stack([c["body_a"], c["face_a"], c["body_b"], c["face_b"]], axis=1)

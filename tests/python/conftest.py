# Shared by the Python tests (docs/python.md): the module from build/python (PYTHONPATH, set by
# ctest), the bvhlab program beside it, and small scenes.
import os
import pathlib

import numpy as np
import pytest

import bvhlab

REPOSITORY = pathlib.Path(__file__).resolve().parents[2]


@pytest.fixture(scope="session")
def program():
    """The bvhlab program of the same build (BVHLAB_BINARY, else build/bvhlab)."""
    path = pathlib.Path(os.environ.get("BVHLAB_BINARY", REPOSITORY / "build" / "bvhlab"))
    if not path.exists():
        pytest.skip(f"{path} not built")
    return path


@pytest.fixture(scope="session")
def default_scene():
    """The embedded default scene, as `bvhlab render` without --scene sees it."""
    return bvhlab.load_scene()


@pytest.fixture(scope="session")
def quad_scene():
    """Two triangles covering the unit square in the plane z = 0."""
    vertices = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], dtype=np.float32)
    return bvhlab.Scene.from_arrays(vertices, np.array([[0, 1, 2], [0, 2, 3]]))


def rays_down(n, seed=1):
    """n rays from z = 1 straight down onto [-0.5, 1.5]^2: some hit the quad, some miss."""
    rng = np.random.default_rng(seed)
    origins = np.column_stack([rng.uniform(-0.5, 1.5, (n, 2)), np.ones(n)]).astype(np.float32)
    directions = np.tile(np.array([0, 0, -1], dtype=np.float32), (n, 1))
    return origins, directions

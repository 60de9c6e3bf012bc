# bvhlab.load_scene and bvhlab.Scene: what the CLI reads, as NumPy views, and its errors.
import gzip

import numpy as np
import pytest

import bvhlab

QUAD_OBJ = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3\nf 1 3 4\n"


def test_input_error_is_a_value_error():
    assert issubclass(bvhlab.InputError, ValueError)


def test_default_scene_arrays(default_scene):
    vertices, indices = default_scene.vertices, default_scene.indices
    assert default_scene.triangle_count == len(indices) > 0
    assert vertices.dtype == np.float32 and vertices.shape[1] == 3
    assert indices.dtype == np.uint32 and indices.shape[1] == 3
    assert indices.max() < len(vertices)
    with pytest.raises(ValueError):
        vertices[0, 0] = 1.0  # a read-only view of the scene's own array
    lower, upper = np.array(default_scene.bounds)
    used = vertices[indices.ravel()]
    assert np.all(lower <= used.min(axis=0) + 1e-6) and np.all(used.max(axis=0) <= upper + 1e-6)


def test_from_arrays(quad_scene):
    assert quad_scene.triangle_count == 2
    assert quad_scene.bounds == ((0.0, 0.0, 0.0), (1.0, 1.0, 0.0))
    np.testing.assert_array_equal(quad_scene.indices, [[0, 1, 2], [0, 2, 3]])


@pytest.mark.parametrize("compress", [False, True])
def test_obj_file_and_gz(tmp_path, quad_scene, compress):
    path = tmp_path / ("quad.obj.gz" if compress else "quad.obj")
    path.write_bytes(gzip.compress(QUAD_OBJ.encode()) if compress else QUAD_OBJ.encode())
    scene = bvhlab.load_scene(str(path))
    np.testing.assert_array_equal(scene.vertices, quad_scene.vertices)
    np.testing.assert_array_equal(scene.indices, quad_scene.indices)


def test_missing_file_has_the_cli_message(tmp_path):
    with pytest.raises(bvhlab.InputError, match="no such file"):
        bvhlab.load_scene(str(tmp_path / "nothing.obj"))


def test_malformed_file_names_file_and_line(tmp_path):
    path = tmp_path / "bad.obj"
    path.write_text("v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 9\n")
    with pytest.raises(bvhlab.InputError, match=rf"^{path}:4: .*out of range"):
        bvhlab.load_scene(str(path))


def test_unknown_env_key_in_load():
    with pytest.raises(bvhlab.InputError, match="Camera::widht"):
        bvhlab.load_scene(env={"Camera::widht": 64})


@pytest.mark.parametrize("vertices, indices, message", [
    (np.zeros((4, 2)), [[0, 1, 2]], "vertices"),
    (np.zeros((0, 3)), [[0, 1, 2]], "vertices"),
    (np.eye(3), [[0, 1, 3]], "out of range"),
    (np.eye(3), [[0, 1, -1]], "out of range"),
    (np.eye(3), np.zeros((0, 3), dtype=int), "indices"),
    (np.eye(3), [[0, 1]], "indices"),
])
def test_from_arrays_rejects(vertices, indices, message):
    with pytest.raises(bvhlab.InputError, match=message):
        bvhlab.Scene.from_arrays(vertices, indices)


def test_from_arrays_rejects_only_degenerate_triangles():
    with pytest.raises(bvhlab.InputError):
        bvhlab.Scene.from_arrays(np.zeros((3, 3)), [[0, 1, 2]])

# BVHRAYS1 / BVHHITS1 files (docs/file-formats.md) and the bench's ray sets from Python.
import math

import numpy as np
import pytest

import bvhlab
from conftest import rays_down


def test_rays_round_trip(tmp_path):
    origins, directions = rays_down(10)
    tmax = np.linspace(1, 10, 10)
    bvhlab.write_rays(tmp_path / "r.bin", origins, directions, tmin=0.25, tmax=tmax)
    rays = bvhlab.read_rays(tmp_path / "r.bin")
    np.testing.assert_array_equal(rays["origins"], origins)
    np.testing.assert_array_equal(rays["directions"], directions)
    assert np.all(rays["tmin"] == 0.25)
    np.testing.assert_array_equal(rays["tmax"], tmax.astype(np.float32))


def test_strided_and_empty_rays_written(tmp_path):
    origins, directions = rays_down(10)
    table = np.column_stack([origins, directions]).astype(np.float64)
    bvhlab.write_rays(tmp_path / "r.bin", table[:, :3], table[:, 3:])
    rays = bvhlab.read_rays(tmp_path / "r.bin")
    np.testing.assert_array_equal(rays["origins"], origins)
    np.testing.assert_array_equal(rays["directions"], directions)
    bvhlab.write_rays(tmp_path / "none.bin", table[:0, :3], table[:0, 3:])
    rays = bvhlab.read_rays(tmp_path / "none.bin")
    assert rays["origins"].shape == (0, 3) and rays["tmax"].shape == (0,)


def test_hits_round_trip(tmp_path, quad_scene):
    hits = bvhlab.build(quad_scene, "sahbvh").intersect(*rays_down(50))
    assert (hits["prim"] == -1).any() and (hits["prim"] >= 0).any()
    bvhlab.write_hits(tmp_path / "h.bin", hits)
    np.testing.assert_array_equal(bvhlab.read_hits(tmp_path / "h.bin"), hits)


def test_bad_files(tmp_path):
    with pytest.raises(bvhlab.InputError, match="cannot open"):
        bvhlab.read_rays(tmp_path / "none.bin")
    (tmp_path / "junk.bin").write_bytes(b"NOTRAYS!" + bytes(8))
    with pytest.raises(bvhlab.InputError, match="bad magic"):
        bvhlab.read_hits(tmp_path / "junk.bin")
    with pytest.raises(bvhlab.InputError, match="fields t, prim, u, v"):
        bvhlab.write_hits(tmp_path / "h.bin", np.zeros(3))


def test_bench_rays(default_scene):
    scene = bvhlab.load_scene(env={"Camera::width": 16, "Camera::height": 8})
    primary = bvhlab.rays(scene)
    assert primary["origins"].shape == (128, 3) and primary["directions"].dtype == np.float32
    shadow = bvhlab.rays(scene, "shadow")
    assert len(shadow["origins"]) > 0
    with pytest.raises(bvhlab.InputError, match="primary, shadow or incoherent"):
        bvhlab.rays(scene, "secondary")
    assert math.isinf(primary["tmax"][0])
    # By name, and with the camera's size given to rays() instead of the load: the same rays.
    for rays in (bvhlab.rays("", env={"Camera::width": 16, "Camera::height": 8}),
                 bvhlab.rays(default_scene, env={"Camera::width": 16, "Camera::height": 8})):
        for name in primary:
            np.testing.assert_array_equal(rays[name], primary[name])

# bvhlab.build and Accelerator.intersect / occluded over NumPy arrays, and their errors.
import math

import numpy as np
import pytest

import bvhlab
from conftest import rays_down

OURS = [a["name"] for a in bvhlab.accelerators() if not a["plugin"]]


def test_accelerators_listed():
    names = {a["name"]: a for a in bvhlab.accelerators()}
    assert {"sahbvh", "sahbvh8", "embree", "naive"} <= names.keys()
    assert all(a["description"] for a in names.values())


@pytest.mark.parametrize("name", OURS)
def test_quad_hits(quad_scene, name):
    accel = bvhlab.build(quad_scene, name)
    origins, directions = rays_down(1000)
    hits = accel.intersect(origins, directions, counters=accel.has_counters)
    inside = np.all((origins[:, :2] > 0.001) & (origins[:, :2] < 0.999), axis=1)
    outside = np.all((origins[:, :2] < -0.001) | (origins[:, :2] > 1.001), axis=1)
    assert np.all(hits["t"][inside] == 1.0) and np.all(hits["prim"][inside] >= 0)
    assert np.all(np.isinf(hits["t"][outside])) and np.all(hits["prim"][outside] == -1)
    np.testing.assert_array_equal(accel.occluded(origins, directions), hits["prim"] >= 0)
    if accel.has_counters:
        assert hits["n_tr"].sum() > 0 and hits["n_it"][inside].min() >= 1


def test_stats(default_scene):
    stats = bvhlab.build(default_scene, "sahbvh8", env={"BVH::bins": 32}).stats
    assert stats["build_ms"] > 0 and stats["primitives"] > 0
    assert stats["nodes"] > stats["leaves"] > 0 and stats["sah"] > 0 and stats["bytes"] > 0
    assert bvhlab.build(default_scene, "embree").stats["nodes"] is None  # its tree is invisible


def test_float64_and_per_ray_intervals(quad_scene):
    accel = bvhlab.build(quad_scene, "sahbvh")
    origins, directions = rays_down(100)
    hits32 = accel.intersect(origins, directions)
    hits64 = accel.intersect(origins.astype(np.float64), directions.astype(np.float64))
    np.testing.assert_array_equal(hits32, hits64)
    tmax = np.where(np.arange(100) % 2 == 0, 0.5, math.inf)  # even rays stop short of the quad
    short = accel.intersect(origins, directions, tmax=tmax)
    assert np.all(short["prim"][::2] == -1)
    np.testing.assert_array_equal(short[1::2], hits32[1::2])
    assert np.all(accel.intersect(origins, directions, tmin=1.5)["prim"] == -1)


def test_nan_rays_miss(quad_scene):
    accel = bvhlab.build(quad_scene, "sahbvh8")
    origins = np.array([[0.5, 0.5, 1.0], [math.nan, 0.5, 1.0]], dtype=np.float32)
    directions = np.array([[0, 0, -1], [0, 0, -1]], dtype=np.float32)
    assert list(accel.intersect(origins, directions)["prim"] >= 0) == [True, False]
    assert list(accel.occluded(origins, directions)) == [True, False]


GOOD = np.zeros((4, 3), dtype=np.float32)


@pytest.mark.parametrize("origins, directions, kwargs, message", [
    (np.zeros((4, 2), dtype=np.float32), GOOD, {}, r"origins: expected shape \(N, 3\)"),
    (np.zeros(12, dtype=np.float32), GOOD, {}, r"origins: expected shape \(N, 3\)"),
    (np.zeros((4, 3), dtype=np.int32), GOOD, {}, "origins: expected float32 or float64"),
    (np.zeros((4, 3), dtype=">f4"), GOOD, {}, "origins: expected float32 or float64"),
    (GOOD.tolist(), GOOD, {}, "origins: expected a NumPy array"),
    (np.zeros((8, 3), dtype=np.float32)[::2], GOOD, {}, "origins: not C-contiguous"),
    (np.zeros((0, 3), dtype=np.float32), np.zeros((0, 3), dtype=np.float32), {}, "origins: empty"),
    (GOOD, np.zeros((5, 3), dtype=np.float32), {}, "directions: 5 rows where origins has 4"),
    (GOOD, GOOD, {"tmin": np.zeros(3)}, "tmin: 3 rows where origins has 4"),
    (GOOD, GOOD, {"tmax": "far"}, "tmax: expected a number"),
    (GOOD, GOOD, {"threads": -1}, "threads -1"),
])
def test_bad_rays(quad_scene, origins, directions, kwargs, message):
    accel = bvhlab.build(quad_scene, "sahbvh")
    for query in (accel.intersect, accel.occluded):
        with pytest.raises(bvhlab.InputError, match=message):
            query(origins, directions, **kwargs)


@pytest.mark.parametrize("name, env, message", [
    ("sahbvh9", None, "unknown accelerator 'sahbvh9'.*sahbvh8"),
    ("sahbvh", {"BVH::binz": 32}, "-DBVH::binz: unknown key.*BVH::bins"),
    ("sahbvh", {"BVH::bins": 0}, "-DBVH::bins"),
    ("sahbvh", {"BVH::bins": "many"}, "-DBVH::bins"),
    ("sahbvh", {32: "BVH::bins"}, "env: keys are strings"),
])
def test_bad_build(quad_scene, name, env, message):
    with pytest.raises(bvhlab.InputError, match=message):
        bvhlab.build(quad_scene, name, env=env)


def test_missing_plugin(tmp_path):
    with pytest.raises(bvhlab.InputError, match="nothing.so"):
        bvhlab.load_plugin(tmp_path / "nothing.so")

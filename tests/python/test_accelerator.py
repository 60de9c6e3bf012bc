# bvhlab.build and Accelerator.intersect / occluded over NumPy arrays, and their errors.
import math
import tracemalloc

import numpy as np
import pytest

import bvhlab
from conftest import rays_down

OURS = [a["name"] for a in bvhlab.accelerators() if not a["plugin"]]


def test_accelerators_listed():
    names = {a["name"]: a for a in bvhlab.accelerators()}
    assert {"sahbvh", "sahbvh8", "embree", "naive"} <= names.keys()
    assert all(a["description"] for a in names.values())


def test_accelerators_list_the_plugins_bvhlab_ships():
    names = {a["name"]: a for a in bvhlab.accelerators()}
    for plugin in ("grid", "octree", "kdtree"):
        assert plugin in names, sorted(names)
        assert names[plugin]["plugin"].endswith(f"/{plugin}.so"), names[plugin]


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


@pytest.mark.parametrize("name", ["sahbvh8", "sahbvh", "naive"])
def test_answers_equal_with_and_without_counters(default_scene, name):
    """counters=False asks for queries that count nothing; the answers are those that count, bit for bit."""
    accel = bvhlab.build(default_scene, name)
    rays = bvhlab.rays(default_scene, env={"Camera::width": 40, "Camera::height": 30})
    counted, uncounted = accel.intersect(**rays, counters=True), accel.intersect(**rays)
    assert counted["n_tr"].sum() > 0
    for field in ("t", "prim", "u", "v"):
        assert counted[field].tobytes() == uncounted[field].tobytes(), field
    occluded = accel.occluded(**rays, counters=True)
    np.testing.assert_array_equal(occluded["occluded"], accel.occluded(**rays))


@pytest.mark.parametrize("name", ["sahbvh8", "sahbvh4", "embree"])
@pytest.mark.parametrize("kind", ["primary", "shadow", "incoherent"])
def test_answers_equal_under_either_coherence_hint(default_scene, name, kind):
    """coherent= only chooses a traversal: bvhlab's answers are the same bit for bit, Embree's within hitsAgree."""
    accel = bvhlab.build(default_scene, name)
    rays = bvhlab.rays(default_scene, kind, env={"Camera::width": 40, "Camera::height": 30})
    coherent, incoherent = accel.intersect(**rays, coherent=True), accel.intersect(**rays, coherent=False)
    if name == "embree":
        both = np.isfinite(coherent["t"]) & np.isfinite(incoherent["t"])
        np.testing.assert_array_equal(np.isfinite(coherent["t"]), np.isfinite(incoherent["t"]))
        assert np.all(np.abs(coherent["t"][both] - incoherent["t"][both]) <= 1e-4 * np.maximum(1, np.abs(coherent["t"][both])))
    else:
        for field in ("t", "prim", "u", "v"):
            assert coherent[field].tobytes() == incoherent[field].tobytes(), field
        np.testing.assert_array_equal(accel.occluded(**rays, coherent=True), accel.occluded(**rays))


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


def layouts(origins, directions):
    """The rays in layouts NumPy makes without a copy, as {name: (origins, directions, tmax)}."""
    n = len(origins)
    table = np.column_stack([origins, directions, np.full(n, np.inf)])  # float64, a ray per row
    table32 = table.astype(np.float32)
    reversed_origins = origins[::-1].copy()
    record = np.dtype([("flag", "u1"), ("origin", "<f4", 3), ("direction", "<f4", 3)])  # packed: unaligned
    records = np.zeros(n, dtype=record)
    records["origin"], records["direction"] = origins, directions
    return {
        "columns of a float64 table": (table[:, 0:3], table[:, 3:6], table[:, 6]),
        "columns of a float32 table": (table32[:, :3], table32[:, 3:6], table32[:, 6]),
        "every other row": (np.repeat(origins, 2, axis=0)[::2], np.repeat(directions, 2, axis=0)[1::2], np.inf),
        "reversed rows": (reversed_origins[::-1], directions, np.inf),
        "Fortran order": (np.asfortranarray(origins), np.asfortranarray(directions), np.inf),
        "broadcast direction": (origins, np.broadcast_to(directions[0], directions.shape), np.inf),
        "fields of a packed record": (records["origin"], records["direction"], np.inf),
    }


@pytest.mark.parametrize("layout", layouts(*rays_down(1)).keys())
def test_strided_rays_read_in_place(quad_scene, layout):
    accel = bvhlab.build(quad_scene, "sahbvh")
    origins, directions = rays_down(300)
    strided_origins, strided_directions, tmax = layouts(origins, directions)[layout]
    assert not strided_origins.flags.c_contiguous or not strided_directions.flags.c_contiguous
    for query in ("intersect", "occluded"):
        expected = getattr(accel, query)(origins, directions, counters=True)
        answers = getattr(accel, query)(strided_origins, strided_directions, tmax=tmax, counters=True)
        np.testing.assert_array_equal(answers, expected)


def test_strided_rays_are_not_copied(quad_scene):
    accel = bvhlab.build(quad_scene, "sahbvh")
    n = 200_000
    table = np.zeros((n, 7))  # float64 rows: origin, direction, tmax
    table[:, :3], table[:, 5], table[:, 6] = (0.5, 0.5, 1.0), -1.0, 2.0  # down onto the quad's middle
    tracemalloc.start()
    try:
        occluded = accel.occluded(table[:, :3], table[:, 3:6], tmax=table[:, 6])
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert occluded.all()
    assert peak < 2 * n  # the answer, n bools; a copy of tmax alone would take 4n or 8n bytes


@pytest.mark.parametrize("dtype", [np.float32, np.float64])
def test_empty_rays_give_empty_answers(quad_scene, dtype):
    accel = bvhlab.build(quad_scene, "sahbvh")
    empty = np.empty((0, 3), dtype=dtype)
    for query in ("intersect", "occluded"):
        for counters in (False, True):
            expected = getattr(accel, query)(*rays_down(2), counters=counters)
            answers = getattr(accel, query)(empty, empty, tmin=np.empty(0), tmax=np.empty(0), counters=counters)
            assert answers.shape == (0,) and answers.dtype == expected.dtype, (query, counters)


def test_counters_of_a_structure_without_counters_are_nan(quad_scene):
    origins, directions = rays_down(200)
    counted, uncounted = bvhlab.build(quad_scene, "sahbvh"), bvhlab.build(quad_scene, "embree")
    assert counted.has_counters and not uncounted.has_counters
    for query in ("intersect", "occluded"):
        ours = getattr(counted, query)(origins, directions, counters=True)
        embree = getattr(uncounted, query)(origins, directions, counters=True)
        assert embree.dtype == ours.dtype  # one layout for every structure
        for counter in ("n_it", "n_tr"):
            assert np.isnan(embree[counter]).all(), (query, counter)
            assert np.isfinite(ours[counter]).all() and ours[counter].sum() > 0, (query, counter)


GOOD = np.zeros((4, 3), dtype=np.float32)


@pytest.mark.parametrize("origins, directions, kwargs, message", [
    (np.zeros((4, 2), dtype=np.float32), GOOD, {}, r"origins: expected shape \(N, 3\)"),
    (np.zeros(12, dtype=np.float32), GOOD, {}, r"origins: expected shape \(N, 3\)"),
    (np.zeros((4, 3), dtype=np.int32), GOOD, {}, "origins: expected float32 or float64"),
    (np.zeros((4, 3), dtype=">f4"), GOOD, {}, "origins: expected float32 or float64"),
    (GOOD.tolist(), GOOD, {}, "origins: expected a NumPy array"),
    (np.zeros((0, 2), dtype=np.float32), np.zeros((0, 3), dtype=np.float32), {}, r"origins: expected shape \(N, 3\)"),
    (np.zeros((0, 3), dtype=np.float32), GOOD, {}, "directions: 4 rows where origins has 0"),
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


@pytest.mark.parametrize("name,env", [("sahbvh", {}), ("sahbvh8", {}), ("naive", {}), ("embree", {}),
                                      ("embree", {"Embree::quality": "refit"})])
def test_update_after_the_quad_moved(quad_scene, name, env):
    """accel.update(scene): the quad lowered and shifted answers as a fresh build over it; Embree has an update
    at Embree::quality=refit only."""
    accel = bvhlab.build(quad_scene, name, env=env)
    square = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], dtype=np.float32)
    moved = bvhlab.Scene.from_arrays(square + np.float32([0.25, 0, -0.5]), np.array([[0, 1, 2], [0, 2, 3]]))
    updated = accel.update(moved)
    assert updated == (name != "embree" or bool(env))
    if not updated:
        return
    origins, directions = rays_down(1000)
    hits = accel.intersect(origins, directions)
    fresh = bvhlab.build(moved, name, env=env).intersect(origins, directions)
    np.testing.assert_array_equal(hits["t"], fresh["t"])
    assert np.allclose(hits["t"][hits["prim"] >= 0], 1.5, rtol=1e-6) and np.any(hits["prim"] >= 0)
    if name != "naive":
        with pytest.raises(ValueError, match="built over"):
            accel.update(bvhlab.Scene.from_arrays(square[:3], np.array([[0, 1, 2]])))

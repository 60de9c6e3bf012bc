# An animated scene (.aff) from Python: loaded at a frame or a time, moved by set_time, and a
# structure updated after the move answering as a fresh build over the scene at that time.
import math

import numpy as np
import pytest

import bvhlab

from conftest import REPOSITORY


@pytest.fixture
def moving_aff():
    """tests/support/moving_scene.aff: three frames at t = 0, 1, 2; triangles 1 and 2 move from the
    view's centre at z = 0 to 100 to the side, triangle 0 stays at z = -10; the eye moves back."""
    return str(REPOSITORY / "tests" / "support" / "moving_scene.aff")


def rays_into_the_view(n, seed=2):
    """n rays from z = 20 straight down over [-20, 20]^2 around the view's centre."""
    rng = np.random.default_rng(seed)
    origins = np.column_stack([rng.uniform(-20, 20, (n, 2)), np.full(n, 20.0)]).astype(np.float32)
    return origins, np.tile(np.float32([0, 0, -1]), (n, 1))


def test_frames_and_times(moving_aff):
    scene = bvhlab.load_scene(moving_aff)
    assert (scene.frame_count, scene.start_time, scene.end_time, scene.time) == (3, 0.0, 2.0, 0.0)
    assert [scene.frame_time(k) for k in range(3)] == [0.0, 1.0, 2.0]
    assert scene.vertices[3:, 0].min() == -5.0

    at_frame = bvhlab.load_scene(moving_aff, frame=2)
    from_env = bvhlab.load_scene(moving_aff, env={"Scene::frame": 2})
    at_time = bvhlab.load_scene(moving_aff, time=2.0)
    scene.set_time(scene.frame_time(2))
    assert scene.time == at_frame.time == 2.0
    for other in (at_frame, from_env, at_time):
        np.testing.assert_array_equal(other.vertices, scene.vertices)
    assert scene.vertices[3:, 0].min() == pytest.approx(95.0)
    assert scene.bounds[1][0] == pytest.approx(105.0)
    # The camera moved with it: the frame's primary rays leave from z = 15.
    assert np.all(bvhlab.rays(scene, "primary")["origins"][:, 2] == 15.0)


@pytest.mark.parametrize("name,env", [("sahbvh", {}), ("sahbvh8", {}), ("naive", {}),
                                      ("embree", {"Embree::quality": "refit"})])
def test_update_after_set_time_answers_as_a_fresh_build(moving_aff, name, env):
    scene = bvhlab.load_scene(moving_aff)
    accel = bvhlab.build(scene, name, env=env)
    origins, directions = rays_into_the_view(2000)
    before = accel.intersect(origins, directions)
    assert np.any(before["prim"] >= 1)

    for frame in (1, 2, 0):
        scene.set_time(scene.frame_time(frame))
        with pytest.raises(ValueError, match="moved"):
            accel.intersect(origins, directions)
        assert accel.update(scene)
        hits = accel.intersect(origins, directions)
        fresh = bvhlab.build(bvhlab.load_scene(moving_aff, frame=frame), name, env=env).intersect(origins, directions)
        np.testing.assert_array_equal(hits["prim"], fresh["prim"])
        np.testing.assert_array_equal(hits["t"], fresh["t"])
    np.testing.assert_array_equal(accel.intersect(origins, directions)["prim"], before["prim"])


def test_a_structure_without_an_update_is_built_again(moving_aff):
    scene = bvhlab.load_scene(moving_aff)
    accel = bvhlab.build(scene, "embree")
    scene.set_time(2.0)
    assert not accel.update(scene)
    with pytest.raises(ValueError, match="bvhlab.build again"):
        accel.occluded(*rays_into_the_view(10))
    with pytest.raises(ValueError, match="moved"):
        bvhlab.render(accel)
    hits = bvhlab.build(scene, "embree").intersect(*rays_into_the_view(1000))
    assert not np.any(hits["prim"] >= 1)  # the mover is out of the rays' reach


# Triangle 1 collapses to a point from t = 0 to 1 while triangle 2 grows from one: as many valid
# primitives at t = 1, but others.
SWAP_AFF = """p 3
0 0 -5
10 0 -5
0 10 -5
tpa 2
0
0 0 0 0 0 1
1 0 0 0 0 1
0 1 0 0 0 1
1
0 0 0 0 0 1
0 0 0 0 0 1
0 0 0 0 0 1
tpa 2
0
2 0 0 0 0 1
2 0 0 0 0 1
2 0 0 0 0 1
1
2 0 0 0 0 1
3 0 0 0 0 1
2 1 0 0 0 1
a 0 1 2
"""


@pytest.mark.parametrize("name,env", [("sahbvh", {}), ("sahbvh8", {}), ("naive", {}),
                                      ("embree", {"Embree::quality": "refit"})])
def test_no_update_when_other_primitives_are_valid(tmp_path, name, env):
    path = tmp_path / "swap.aff"
    path.write_text(SWAP_AFF)
    scene = bvhlab.load_scene(str(path))
    accel = bvhlab.build(scene, name, env=env)
    scene.set_time(1.0)
    assert not accel.update(scene)
    with pytest.raises(ValueError, match="moved"):
        accel.intersect(np.float32([[2.2, 0.2, 1]]), np.float32([[0, 0, -1]]))
    hit = bvhlab.build(scene, name, env=env).intersect(np.float32([[2.2, 0.2, 1]]), np.float32([[0, 0, -1]]))
    assert (hit["prim"][0], hit["t"][0]) == (2, 1.0)


def test_still_scenes_and_errors(moving_aff, quad_scene):
    assert (quad_scene.frame_count, quad_scene.start_time, quad_scene.end_time) == (1, 0.0, 0.0)
    accel = bvhlab.build(quad_scene, "sahbvh")
    quad_scene.set_time(3.0)  # nothing moves, nothing to update
    accel.intersect(*rays_into_the_view(10))
    with pytest.raises(ValueError, match="frame 1: the scene 'arrays' has 1 frame, 0 to 0"):
        quad_scene.frame_time(1)
    with pytest.raises(ValueError, match="frame 3: the scene 'moving_scene' has 3 frames, 0 to 2"):
        bvhlab.load_scene(moving_aff, frame=3)
    with pytest.raises(ValueError, match="Scene::frame 3 .*moving_scene.aff has 3 frames, 0 to 2"):
        bvhlab.load_scene(moving_aff, env={"Scene::frame": 3})
    with pytest.raises(ValueError, match="a frame or a time, not both"):
        bvhlab.load_scene(moving_aff, frame=1, time=1.0)
    with pytest.raises(ValueError, match="finite"):
        bvhlab.load_scene(moving_aff).set_time(math.nan)

# bvhlab.render: bvhlab render's image, per-pixel outputs and statistics as arrays and a dict.
import json
import math
import subprocess

import numpy as np
import pytest

import bvhlab

SIZE = {"Camera::width": 40, "Camera::height": 30}


def test_render_matches_the_cli(program, default_scene, tmp_path):
    accel = bvhlab.build(default_scene, "sahbvh8")
    result = bvhlab.render(accel, env=SIZE)
    assert result["image"].shape == (30, 40, 3) and result["heatmap"].shape == (30, 40)
    seen = result["prim"] >= 0
    assert seen.any() and np.all(np.isfinite(result["depth"][seen])) and np.all(np.isinf(result["depth"][~seen]))
    assert np.all(result["heatmap"] > 0)
    out = tmp_path / "render"
    subprocess.run([program, "render", "--out", out, "-DASDS::type=sahbvh8"] + [f"-D{k}={v}" for k, v in SIZE.items()],
                   check=True, capture_output=True)
    expected = json.loads((tmp_path / "render.json").read_text())
    stats = result["stats"]
    for query in ("primary", "shadow"):
        for figure in ("queries", "n_it", "n_tr"):
            assert stats[query][figure] == expected[query][figure], (query, figure)
    assert stats["sah"] == expected["sah"] and stats["nodes"] == expected["nodes"]


def test_render_rejects_bad_env(default_scene):
    accel = bvhlab.build(default_scene, "sahbvh")
    with pytest.raises(bvhlab.InputError, match="-DCamera::widht: unknown key"):
        bvhlab.render(accel, env={"Camera::widht": 40})
    with pytest.raises(bvhlab.InputError, match="threads -2"):
        bvhlab.render(accel, threads=-2)


def test_render_counters_of_a_structure_without_counters_are_nan(default_scene):
    for name, counted in (("sahbvh8", True), ("embree", False)):
        result = bvhlab.render(bvhlab.build(default_scene, name), env=SIZE)
        for image in ("heatmap", "n_it"):
            assert np.isfinite(result[image]).all() if counted else np.isnan(result[image]).all(), (name, image)
        for query in ("primary", "shadow"):
            for figure in ("n_it", "n_tr"):
                value = result["stats"][query][figure]
                assert math.isfinite(value) if counted else math.isnan(value), (name, query, figure)

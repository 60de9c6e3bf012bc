# The hits of every accelerator of ours through Python equal those of `bvhlab raycast` on the
# same rays: the bench's primary and shadow rays of the default scene, and rays with a NaN.
import subprocess

import numpy as np
import pytest

import bvhlab

OURS = [a["name"] for a in bvhlab.accelerators() if not a["plugin"]]


@pytest.fixture(scope="module")
def ray_files(tmp_path_factory):
    scene = bvhlab.load_scene(env={"Camera::width": 48, "Camera::height": 32})
    folder = tmp_path_factory.mktemp("raycast")
    files = {}
    for kind in ("primary", "shadow"):
        rays = bvhlab.rays(scene, kind)
        rays["origins"][::97, 1] = np.nan  # answered as misses by both
        files[kind] = folder / f"{kind}.rays"
        bvhlab.write_rays(files[kind], **rays)
    return scene, files


@pytest.mark.parametrize("name", OURS)
def test_python_equals_raycast(program, ray_files, tmp_path, name):
    scene, files = ray_files
    accel = bvhlab.build(scene, name)
    for kind, any_hit in (("primary", False), ("shadow", True)):
        out = tmp_path / f"{kind}.hits"
        subprocess.run([program, "raycast", "--rays", files[kind], "--out", out, f"-DASDS::type={name}"]
                       + (["--any"] if any_hit else []), check=True, capture_output=True)
        expected = bvhlab.read_hits(out)
        rays = bvhlab.read_rays(files[kind])
        if any_hit:
            np.testing.assert_array_equal(accel.occluded(**rays), expected["prim"] >= 0)
        else:
            hits = accel.intersect(**rays)
            assert (hits["prim"] >= 0).sum() > len(hits) // 4  # the scene is seen
            np.testing.assert_array_equal(hits, expected)

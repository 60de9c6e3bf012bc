# accel.intersect on the rays of a BVHRAYS1 file against `bvhlab raycast` on the same file
# (docs/python.md, "Cost of the binding"): 10 alternating runs each, medians and minima of wall
# time per ray (Python: the whole call; raycast: its T_R). The hits of the last pair must agree.
# PYTHONPATH=build/python /usr/bin/python3 docs/plots/python_vs_raycast.py build/bvhlab sibenik rays.bin sahbvh8 1
import re
import statistics
import subprocess
import sys
import time

import bvhlab

program, scene_name, rays_file, name, threads = sys.argv[1:6]
hits_file = rays_file + ".hits"
scene = bvhlab.load_scene(scene_name)
accel = bvhlab.build(scene, name)
rays = bvhlab.read_rays(rays_file)
n = len(rays["origins"])
py_us, cli_us = [], []
for _ in range(10):
    start = time.perf_counter()
    hits = accel.intersect(**rays, threads=int(threads))
    py_us.append((time.perf_counter() - start) / n * 1e6)
    out = subprocess.run([program, "raycast", "--scene", scene_name, "--rays", rays_file, "--out", hits_file,
                          f"-DASDS::type={name}", "--threads", threads], check=True, capture_output=True, text=True).stdout
    cli_us.append(float(re.search(r"T_R ([0-9.]+) us", out).group(1)))
assert (bvhlab.read_hits(hits_file) == hits).all()
print(f"{n} rays, {name}, {threads} threads: python median {statistics.median(py_us):.4f} min {min(py_us):.4f}, "
      f"raycast median {statistics.median(cli_us):.4f} min {min(cli_us):.4f}, ratios {statistics.median(py_us) / statistics.median(cli_us):.3f} {min(py_us) / min(cli_us):.3f}")

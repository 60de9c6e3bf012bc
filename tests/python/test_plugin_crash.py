# A crash inside a plugin still ends the Python process by its signal, but first names the
# plugin, the call and its ray on stderr (framework/core/fatal_signal_report.h).
import os
import signal
import subprocess
import sys

import pytest

CRASH = """
import sys
import numpy as np
import bvhlab
bvhlab.load_plugin(sys.argv[1])
scene = bvhlab.Scene.from_arrays(np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0]], dtype=np.float32), np.array([[0, 1, 2]]))
accel = bvhlab.build(scene, "crashing")
accel.intersect(np.array([[0.25, 0.25, -1]], dtype=np.float32), np.array([[0, 0, 1]], dtype=np.float32))
"""


def test_a_crash_in_a_plugin_names_the_plugin_the_call_and_the_ray(program):
    plugin = program.parent / "test_plugins" / "crashing.so"
    if not plugin.exists():
        pytest.skip(f"{plugin} not built")
    result = subprocess.run([sys.executable, "-c", CRASH, str(plugin)], capture_output=True, text=True, env=os.environ)
    assert result.returncode == -signal.SIGSEGV, result.stderr
    assert (f"bvhlab: SIGSEGV (Segmentation fault) in plugin {plugin}, accelerator 'crashing': findNearestBatch() "
            "of the ray org=(0.25, 0.25, -1) dir=(0, 0, 1) t in [0, inf]") in result.stderr, result.stderr

# `import bvhlab` under a Python that cannot import NumPy says that NumPy is missing and how to
# get it (apps/python/module.cpp), not pybind11's "initialization failed".
import os
import subprocess
import sys

WITHOUT_NUMPY = """
import sys
sys.modules["numpy"] = None  # importing numpy now fails, as in a Python without it
import bvhlab
"""


def test_import_without_numpy_says_numpy_is_missing_and_how_to_get_it():
    result = subprocess.run([sys.executable, "-c", WITHOUT_NUMPY], capture_output=True, text=True, env=os.environ)
    assert result.returncode != 0
    assert "bvhlab needs NumPy, which this Python" in result.stderr, result.stderr
    assert "python3-numpy" in result.stderr, result.stderr
    assert "initialization failed" not in result.stderr, result.stderr

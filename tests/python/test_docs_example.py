# docs/python.md's examples run exactly as written: each python block, the builders' on the
# embedded scene, the rays' and the animation's compared with the output the page shows after it.
import os
import pathlib
import re
import subprocess
import sys

import pytest

from conftest import REPOSITORY

TEXT = (REPOSITORY / "docs" / "python.md").read_text()
# The animation example reads BART's museum from the default Scene::dir, the shared scenes beside
# the repository, which a fresh machine may not have.
MUSEUM = REPOSITORY.parent / "shared" / "scenes" / "bart" / "museum" / "museum5.aff"
BLOCKS = re.findall(r"```python\n(.*?)```", TEXT, re.S)


def run(block, tmp_path, *arguments):
    script = tmp_path / "example.py"
    script.write_text(block)
    result = subprocess.run([sys.executable, script, *arguments], capture_output=True, text=True, env=os.environ)
    assert result.returncode == 0, result.stderr
    return result.stdout


def test_every_block_is_tested():
    assert [block.splitlines()[0] for block in BLOCKS] == [
        "# Rays as NumPy holds them: columns of a table of rays, an empty batch, and the counters of a",
        "# An animated scene frame by frame: the structure updated after each move answers as a fresh build.",
        "# Trace time against SAH for bvhlab's builders on one scene (docs/builders.md), one thread.",
    ]


def test_numpy_rays_example(tmp_path):
    shown = re.search(r"```python\n# Rays as NumPy.*?```\n\nSaved as .*? prints .*?:\n\n```\n(.*?)```", TEXT, re.S)
    assert shown, "the rays example is followed by 'Saved as ... prints ...:' and its output"
    assert run(BLOCKS[0], tmp_path) == shown.group(1)


def test_animation_example(tmp_path):
    if not MUSEUM.exists():
        pytest.skip(f"{MUSEUM} is not here")
    shown = re.search(r"```python\n# An animated scene.*?```\n\nIt prints .*?:\n\n```\n(.*?)```", TEXT, re.S)
    assert shown, "the animation example is followed by 'It prints ...:' and its output"
    assert run(BLOCKS[1], tmp_path) == shown.group(1)


def test_builders_example(tmp_path):
    out = tmp_path / "builders.png"
    stdout = run(BLOCKS[2], tmp_path, "", out)
    assert out.read_bytes().startswith(b"\x89PNG")
    assert f"wrote {out}" in stdout

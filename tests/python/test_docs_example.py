# docs/python.md's example runs exactly as written (its python block, on the embedded scene).
import os
import pathlib
import re
import subprocess
import sys

from conftest import REPOSITORY


def test_builders_example(tmp_path):
    text = (REPOSITORY / "docs" / "python.md").read_text()
    blocks = re.findall(r"```python\n(.*?)```", text, re.S)
    assert len(blocks) == 1
    script = tmp_path / "builders_sah.py"
    script.write_text(blocks[0])
    out = tmp_path / "builders.png"
    result = subprocess.run([sys.executable, script, "", out], capture_output=True, text=True, env=os.environ)
    assert result.returncode == 0, result.stderr
    assert out.read_bytes().startswith(b"\x89PNG")
    assert f"wrote {out}" in result.stdout

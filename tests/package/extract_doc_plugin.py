#!/usr/bin/python3
"""Writes a plugin example of docs/plugins.md into a folder, as a user pasting it would:
   tests/package/extract_doc_plugin.py DOC FOLDER [N]
The doc's ```cpp and ```cmake blocks alternate, each example one ```cpp block followed by one
```cmake block; N (1 by default) chooses the example. The C++ goes into the file the CMake
block's `SOURCES` names, the CMake into CMakeLists.txt. Prints the plugin's name."""
import pathlib
import re
import sys

doc, folder = pathlib.Path(sys.argv[1]), pathlib.Path(sys.argv[2])
n = int(sys.argv[3]) if len(sys.argv) > 3 else 1
blocks = [(kind, text) for kind, text in re.findall(r"^```(\w*)\n(.*?)^```$", doc.read_text(), flags=re.S | re.M)
          if kind in ("cpp", "cmake")]
kinds = [kind for kind, _ in blocks]
if not kinds or kinds != ["cpp", "cmake"] * (len(kinds) // 2):
    sys.exit(f"{doc}: expected ```cpp and ```cmake blocks in pairs, found {kinds}")
if not 1 <= n <= len(blocks) // 2:
    sys.exit(f"{doc}: no example {n} (it has {len(blocks) // 2})")
cpp, cmake = blocks[2 * n - 2][1], blocks[2 * n - 1][1]
match = re.search(r"bvhlab_add_plugin\((\w+) SOURCES (\S+?)\)", cmake)
if not match:
    sys.exit(f"{doc}: the ```cmake block of example {n} has no bvhlab_add_plugin(NAME SOURCES FILE)")
folder.mkdir(parents=True, exist_ok=True)
(folder / match.group(2)).write_text(cpp)
(folder / "CMakeLists.txt").write_text(cmake)
print(match.group(1))

#!/usr/bin/python3
"""Writes the plugin example of docs/plugins.md into a folder, as a user pasting it would:
   tests/package/extract_doc_plugin.py DOC FOLDER
The doc holds exactly one ```cpp block followed by one ```cmake block; the C++ goes into the
file the CMake block's `SOURCES` names, the CMake into CMakeLists.txt. Prints the plugin's name."""
import pathlib
import re
import sys

doc, folder = pathlib.Path(sys.argv[1]), pathlib.Path(sys.argv[2])
blocks = re.findall(r"^```(\w*)\n(.*?)^```$", doc.read_text(), flags=re.S | re.M)
kinds = [kind for kind, _ in blocks if kind in ("cpp", "cmake")]
if kinds != ["cpp", "cmake"]:
    sys.exit(f"{doc}: expected one ```cpp block then one ```cmake block, found {kinds}")
cpp = next(text for kind, text in blocks if kind == "cpp")
cmake = next(text for kind, text in blocks if kind == "cmake")
match = re.search(r"bvhlab_add_plugin\((\w+) SOURCES (\S+?)\)", cmake)
if not match:
    sys.exit(f"{doc}: the ```cmake block has no bvhlab_add_plugin(NAME SOURCES FILE)")
folder.mkdir(parents=True, exist_ok=True)
(folder / match.group(2)).write_text(cpp)
(folder / "CMakeLists.txt").write_text(cmake)
print(match.group(1))

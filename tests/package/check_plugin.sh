#!/usr/bin/env bash
# The package tests (tests/CMakeLists.txt), each ending in the check that a plugin was built and
# exports bvhlab's two entry points (framework/plugin/plugin_api.h); loading it is not tested here.
#   tests/package/check_plugin.sh out-of-tree BUILD_DIR       find_package(bvhlab) on the installed build
#   tests/package/check_plugin.sh add-subdirectory BUILD_DIR  add_subdirectory(bvhlab) in another project
set -euo pipefail

fail() { echo "check_plugin: $*" >&2; exit 1; }

[ $# -eq 2 ] || fail "usage: $0 out-of-tree|add-subdirectory BUILD_DIR"
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
build=$(cd "$2" && pwd)
work="$build/package-tests/$1"

case "$1" in
  out-of-tree)
    plugins=$(BVHLAB_BUILD="$build" "$here/build_plugin_out_of_tree.sh" "$here/minimal_plugin" "$work")
    expected="$work/build/minimal.so"
    ;;
  add-subdirectory)
    rm -rf "$work" && mkdir -p "$work"
    cmake -S "$here/add_subdirectory" -B "$work" -G Ninja -DCMAKE_BUILD_TYPE=Release -DBVHLAB_SOURCE="$root" \
      || fail "configuring tests/package/add_subdirectory failed"
    # The plugin target only: it pulls bvhlab_core and bvhlab_config, nothing else of bvhlab.
    cmake --build "$work" -j 2 --target subdir_plugin || fail "building the plugin failed"
    expected="$work/subdir_plugin.so"
    plugins=$expected
    ;;
  *) fail "unknown test $1" ;;
esac

echo "built: $plugins"
[ -f "$expected" ] || fail "$expected was not built"
symbols=$(nm -D --defined-only "$expected")
for symbol in bvhlab_plugin_api_version bvhlab_register_plugin; do
  grep -qw "$symbol" <<< "$symbols" || fail "$expected does not export $symbol"
done
echo "$expected exports bvhlab_plugin_api_version and bvhlab_register_plugin"

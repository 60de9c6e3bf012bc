#!/usr/bin/env bash
# Builds a plugin project against an installed bvhlab, as its user would (docs/install.md):
#   tests/package/build_plugin_out_of_tree.sh SOURCE_DIR [WORK_DIR]
# installs the build folder $BVHLAB_BUILD (default: build, relative to the repository root) into
# WORK_DIR/prefix with `cmake --install`, configures SOURCE_DIR (a CMake project that calls
# find_package(bvhlab) and bvhlab_add_plugin) into WORK_DIR/build with -DCMAKE_PREFIX_PATH=prefix
# and Ninja and no build type (the package's default), builds it, and prints the path of every
# .so it built on stdout. WORK_DIR defaults to
# a temporary folder (kept: the paths printed are in it). CMake's output goes to WORK_DIR/*.log,
# shown on stderr when a step fails; the exit status is then non-zero.
set -euo pipefail

fail() { echo "build_plugin_out_of_tree: $*" >&2; exit 1; }

[ $# -ge 1 ] && [ $# -le 2 ] || fail "usage: $0 SOURCE_DIR [WORK_DIR]"
[ -f "$1/CMakeLists.txt" ] || fail "$1 has no CMakeLists.txt"
source_dir=$(cd "$1" && pwd)
if [ $# -eq 2 ]; then
  mkdir -p "$2" || fail "cannot create $2"
  work_dir=$(cd "$2" && pwd)
else
  work_dir=$(mktemp -d "${TMPDIR:-/tmp}/bvhlab-plugin.XXXXXX")
fi
root=$(cd "$(dirname "$0")/../.." && pwd)
build=${BVHLAB_BUILD:-build}
[[ "$build" = /* ]] || build="$root/$build"
[ -f "$build/cmake_install.cmake" ] || fail "$build is not a configured bvhlab build folder (set BVHLAB_BUILD)"

# Runs a step with its output in WORK_DIR/NAME.log, shown on stderr when it fails.
step() {
  local name=$1; shift
  if ! "$@" > "$work_dir/$name.log" 2>&1; then
    cat "$work_dir/$name.log" >&2
    fail "$name failed: $* (log: $work_dir/$name.log)"
  fi
}

prefix="$work_dir/prefix"
rm -rf "$prefix" "$work_dir/build"
step install cmake --install "$build" --prefix "$prefix"
step configure cmake -S "$source_dir" -B "$work_dir/build" -G Ninja -DCMAKE_PREFIX_PATH="$prefix"
step build cmake --build "$work_dir/build" -j 2

mapfile -t built < <(find "$work_dir/build" -name '*.so' -type f -not -path '*/CMakeFiles/*' | sort)
[ ${#built[@]} -gt 0 ] || fail "the build of $source_dir made no .so (in $work_dir/build)"
printf '%s\n' "${built[@]}"

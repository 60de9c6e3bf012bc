#!/usr/bin/env bash
# The package tests (tests/CMakeLists.txt), on a plugin example of docs/plugins.md as a user
# pastes it into an empty folder (tests/package/extract_doc_plugin.py; EXAMPLE: 1, the default, is
# the accelerator, 2 the builder):
#   tests/package/check_plugin.sh out-of-tree BUILD_DIR [EXAMPLE]       find_package(bvhlab) on
#       `cmake --install` of BUILD_DIR, configured without a build type as docs/install.md does;
#       the installed bvhlab loads the plugin, finds it optimised, renders with it, runs
#       `bvhlab check` on what it adds (a builder: NAME, NAME4 and NAME8)
#   tests/package/check_plugin.sh add-subdirectory BUILD_DIR [EXAMPLE]  add_subdirectory(bvhlab)
#       in another project, which builds the plugin; it must export bvhlab's three entry points
#   tests/package/check_plugin.sh clang BUILD_DIR [EXAMPLE]    as out-of-tree, the plugin built by
#       clang++ (with libstdc++, Debian's `clang`): the same C++ ABI, so bvhlab loads it, renders
#       with it and checks it on the batch queries
set -euo pipefail

fail() { echo "check_plugin: $*" >&2; exit 1; }

[ $# -eq 2 ] || [ $# -eq 3 ] || fail "usage: $0 out-of-tree|add-subdirectory|clang BUILD_DIR [EXAMPLE]"
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
build=$(cd "$2" && pwd)
example=${3:-1}
work="$build/package-tests/$1-$example"
rm -rf "$work" && mkdir -p "$work"
name=$(/usr/bin/python3 "$here/extract_doc_plugin.py" "$root/docs/plugins.md" "$work/plugin" "$example") \
  || fail "could not take example $example from docs/plugins.md"

case "$1" in
  out-of-tree)
    plugin=$(BVHLAB_BUILD="$build" "$here/build_plugin_out_of_tree.sh" "$work/plugin" "$work")
    [ "$plugin" = "$work/build/$name.so" ] || fail "expected $work/build/$name.so, built: $plugin"
    bvhlab="$work/prefix/bin/bvhlab"
    keys=$("$bvhlab" keys --plugin "$plugin")
    grep -q "| \`$name\` |" <<< "$keys" || fail "bvhlab keys does not list $name"
    accelerators=$name
    grep -q "| \`${name}8\` |" <<< "$keys" && accelerators="$name ${name}4 ${name}8"  # a builder's
    grep -q "bvhlab: no CMAKE_BUILD_TYPE given, building Release" "$work/configure.log" \
      || fail "the package did not say it builds Release (log: $work/configure.log)"
    rendered=$("$bvhlab" render --plugin "$plugin" -DASDS::type="$name" -DCamera::width=32 -DCamera::height=24 \
      --out "$work/render/image" 2>&1) || fail "the installed bvhlab could not render with $name: $rendered"
    ! grep -q "compiled without optimisation" <<< "$rendered" || fail "$name.so is not optimised: $rendered"
    /usr/bin/python3 -c 'import json, sys; sys.exit(not json.load(open(sys.argv[1]))["provenance"]["plugins"][0]["optimized"])' \
      "$work/render/image.json" || fail "the provenance of $work/render/image.json does not say $name.so is optimised"
    for accelerator in $accelerators; do
      "$bvhlab" check --plugin "$plugin" --accel "$accelerator" || fail "bvhlab check failed on $accelerator"
      # Found by name in a plugin folder, as docs/plugins.md says.
      BVHLAB_PLUGIN_PATH="$work/build" "$bvhlab" check --accel "$accelerator" --checks batch \
        || fail "bvhlab check did not find $accelerator by name in BVHLAB_PLUGIN_PATH"
    done
    echo "the installed bvhlab loaded $plugin, rendered with $name and checked $accelerators"
    ;;
  clang)
    command -v clang++ > /dev/null || fail "clang++ is not installed (Debian's clang, ./setup.sh installs it)"
    plugin=$(CXX=clang++ BVHLAB_BUILD="$build" "$here/build_plugin_out_of_tree.sh" "$work/plugin" "$work")
    bvhlab="$work/prefix/bin/bvhlab"
    rendered=$("$bvhlab" render --plugin "$plugin" -DASDS::type="$name" -DCamera::width=16 -DCamera::height=12 \
      --out "$work/render/image" 2>&1) || fail "the installed bvhlab could not render with the clang-built $name: $rendered"
    compiler=$(/usr/bin/python3 -c 'import json, sys; print(json.load(open(sys.argv[1]))["provenance"]["plugins"][0]["compiler"])' \
      "$work/render/image.json")
    [[ "$compiler" = Clang* ]] || fail "$plugin was built by $compiler, not by clang++"
    "$bvhlab" check --plugin "$plugin" --accel "$name" --checks batch || fail "bvhlab check failed on the clang-built $name"
    echo "the installed bvhlab loaded $plugin, built by $compiler, rendered with $name and checked it"
    ;;
  add-subdirectory)
    cmake -S "$here/add_subdirectory" -B "$work/build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
      -DBVHLAB_SOURCE="$root" -DPLUGIN_NAME="$name" -DPLUGIN_SOURCES="$(ls "$work"/plugin/*.cpp | paste -sd';')" \
      || fail "configuring tests/package/add_subdirectory failed"
    # The plugin target only: it builds nothing of bvhlab's (bvhlab::plugin_api is headers).
    cmake --build "$work/build" -j 2 --target "$name" || fail "building the plugin failed"
    plugin="$work/build/$name.so"
    [ -f "$plugin" ] || fail "$plugin was not built"
    symbols=$(nm -D --defined-only "$plugin")
    entry_points="bvhlab_plugin_abi bvhlab_plugin_build_info bvhlab_register_plugin"
    for symbol in $entry_points; do
      grep -qw "$symbol" <<< "$symbols" || fail "$plugin does not export $symbol"
    done
    echo "$plugin exports $entry_points"
    ;;
  *) fail "unknown test $1" ;;
esac

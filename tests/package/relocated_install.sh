#!/usr/bin/env bash
# An installed bvhlab works on its own (the RelocatedInstall test; docs/install.md): installs
# BUILD_DIR into a prefix, moves the prefix, hides the source and build trees behind empty folders
# (a private mount namespace: as if they were deleted), then renders, lists keys, checks a plugin
# of bvhlab's found by name, benches, batches and imports the Python module from the moved prefix,
# from a folder whose env/global.env must not be read; a scene file outside the prefix takes the
# scene env of its name, and defaults the prefix does not hold (Scene::dir, Spd::reference) fail
# naming the key to set. Exit 77 (skipped) without mount namespaces.
#   tests/package/relocated_install.sh BUILD_DIR
set -euo pipefail

fail() { echo "relocated_install: $*" >&2; exit 1; }
[ $# -eq 1 ] || fail "usage: $0 BUILD_DIR"
source_tree=$(cd "$(dirname "$0")/../.." && pwd)
build=$(cd "$1" && pwd)

namespace=(unshare --mount)
"${namespace[@]}" true 2>/dev/null || namespace=(unshare --mount --map-root-user)
"${namespace[@]}" true 2>/dev/null \
  || { echo "relocated_install: no mount namespaces here (needs root or user namespaces): skipped"; exit 77; }

work=$(mktemp -d /tmp/bvhlab-relocated.XXXXXX)
trap 'rm -rf "$work"' EXIT
cmake --install "$build" --prefix "$work/installed" >/dev/null || fail "cmake --install failed"
mv "$work/installed" "$work/moved"
prefix="$work/moved"

# A scene of two triangles, and a folder with an env/global.env that would break any run reading it.
mkdir -p "$work/elsewhere/env"
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 1\nf 1 2 3\nf 2 4 3\n' > "$work/quad.obj"
mkdir -p "$work/data" && cp "$work/quad.obj" "$work/data/a10.obj"  # a scene file named as env/scenes/a10.env's
echo "ASDS::type no_such_structure" > "$work/elsewhere/env/global.env"

cat > "$work/inside.sh" <<INSIDE
set -euo pipefail
fail() { echo "relocated_install: \$*" >&2; exit 1; }
for tree in "$build" "$source_tree"; do mount -t tmpfs none "\$tree"; done  # the build tree may be inside the source tree
[ -z "\$(ls -A "$source_tree")" ] || fail "the source tree is still visible"
cd "$work/elsewhere"
export XDG_CACHE_HOME="$work/cache" HOME="$work/home"
bvhlab="$prefix/bin/bvhlab"
"\$bvhlab" render --threads 1 -DCamera::width=32 -DCamera::height=24 --out "$work/out/default" \
  || fail "render from the moved prefix failed"
[ -f "$work/out/default.json" ] || fail "render wrote no $work/out/default.json"
"\$bvhlab" keys -DASDS::type=grid -DGrid::density=2 | grep -q '^Grid::density 2 ' \
  || fail "bvhlab keys does not take the key of the grid found in the prefix"
"\$bvhlab" check --accel grid:Grid::density=2 --checks agreement,batch || fail "check --accel grid failed"
"\$bvhlab" bench --scenes "$work/quad.obj" --accel sahbvh8,grid --builds 1 --passes 1 --out "$work/out/bench.json" \
  || fail "bench failed"
if /usr/bin/python3 -c 'import matplotlib' 2>/dev/null; then  # bvhlab plot runs the scripts the prefix holds
  "\$bvhlab" plot "$work/out/bench.json" >/dev/null && [ -s "$work/out/bench.png" ] || fail "bvhlab plot of the bench failed"
fi
"\$bvhlab" batch --scenes "$work/quad.obj" --accel grid,sahbvh8 -DCamera::width=16 -DCamera::height=16 \
  --out "$work/out/batch" >/dev/null || fail "batch failed"
ls "$work/cache/bvhlab/scenes/"* >/dev/null 2>&1 || fail "the scene cache is not in \\\$XDG_CACHE_HOME/bvhlab/scenes"
# A scene file takes the camera of the env file naming its name, wherever the file lives.
"\$bvhlab" render --scene "$work/data/a10.obj" --threads 1 -DCamera::width=32 -DCamera::height=24 \
  --out "$work/out/a10" 2>"$work/a10.err" || fail "render of a10.obj failed: \$(cat "$work/a10.err")"
grep -q "^scene env: $prefix/share/bvhlab/env/scenes/a10.env\$" "$work/a10.err" \
  || fail "a10.obj outside Scene::dir did not take env/scenes/a10.env: \$(cat "$work/a10.err")"
grep -q '"14 -13 8"' "$work/out/a10.json" || fail "a10.obj was not seen from a10.env's camera"
# Defaults that point nowhere in a prefix fail naming the key to set.
expect_hint() {  # expect_hint KEY COMMAND...: the command fails, naming KEY's default and how to set it
  local key=\$1; shift
  if "\$@" >"$work/hint.out" 2>&1; then fail "\$* succeeded without \$key's files"; fi
  grep -q "\$key is $prefix/share/shared/.* (its default; set it with -D\$key=" "$work/hint.out" \
    || fail "\$* did not name \$key: \$(cat "$work/hint.out")"
}
expect_hint Scene::dir "\$bvhlab" render --scene a10 --out "$work/out/named"
expect_hint Scene::dir "\$bvhlab" tradeoff --quick --out "$work/out/tradeoff"
expect_hint Spd::reference "\$bvhlab" spd "$work/none.nff" --out "$work/out/spd"
module=\$(find "$prefix" -name 'bvhlab*.so' -path '*-packages*' | head -1)
if [ -n "\$module" ]; then
  PYTHONPATH=\$(dirname "\$module") /usr/bin/python3 -c "
import numpy as np, bvhlab
scene = bvhlab.load_scene('$work/quad.obj')
accel = bvhlab.build(scene, 'grid')
hits = accel.intersect(np.array([[0.25, 0.25, -1.0]], np.float32), np.array([[0, 0, 1.0]], np.float32))
assert hits['t'][0] == 1.0, hits
print('python: grid from the moved prefix hit at t =', hits['t'][0])
" || fail "the Python module from the moved prefix failed"
fi
INSIDE
"${namespace[@]}" bash "$work/inside.sh"
echo "the moved prefix rendered, checked, benched, batched and imported without the source and build trees, found"
echo "a10.obj's scene env by its name and named the keys to set for the defaults it does not hold"

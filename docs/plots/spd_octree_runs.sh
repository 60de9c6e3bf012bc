#!/bin/sh
# The octree beside Havran's octree tables (docs/spd.md, "Havran's octrees"): each shared SPD scene
# with his two subdivisions and two of his traversals at his four maximum depths; then the table.
#   docs/plots/spd_octree_runs.sh [OUT]     (default out/spd_octree; from the repository's root)
set -e
OUT=${1:-out/spd_octree}
for scene in balls mount rings teapot tetra tree; do
    accels=""
    for traversal in octree84 octree93; do
        for subdivision in centre adaptive; do
            for depth in 4 5 6 7; do
                accels="$accels,octree:Octree::traversal=$traversal:Octree::subdivision=$subdivision:Octree::maxDepth=$depth"
            done
        done
    done
    ./build/bvhlab spd ../shared/scenes/nff/$scene.nff --env env/spd.env --threads 1 --accel "${accels#,}" \
        --out "$OUT/$scene" --quiet > /dev/null
done
/usr/bin/python3 docs/plots/spd_octree_table.py --data "$OUT"

#!/bin/sh
# The grid beside Havran's uniform grid (docs/spd.md, "The uniform grid"): each shared SPD scene
# at Woo's D = 1 and D = 10 with N = its NFF objects, at Havran's published resolutions, and at
# D = 1 and D = 10 with the exact overlap tests; then the table.
#   docs/plots/spd_grid_runs.sh [OUT]     (default out/spd_grid; from the repository's root)
set -e
OUT=${1:-out/spd_grid}
run() {  # scene, NFF objects, Havran's resolution at D = 1, at D = 10
    ./build/bvhlab spd ../shared/scenes/nff/$1.nff --env env/spd.env --threads 1 \
        --accel "grid:Grid::density=1:Grid::objects=$2,grid:Grid::density=10:Grid::objects=$2,grid:Grid::resolution=$3,grid:Grid::resolution=$4,grid:Grid::density=1:Grid::objects=$2:Grid::overlap=exact,grid:Grid::density=10:Grid::objects=$2:Grid::overlap=exact" \
        --out "$OUT/$1"
}
run balls 7382 "46 46 3" "103 103 7"
run mount 8196 "20 20 20" "44 44 42"
run rings 8401 "21 20 21" "44 43 44"
run teapot 2292 "28 29 11" "61 61 25"
run tetra 4096 "16 16 16" "35 35 35"
run tree 8191 "52 52 3" "117 118 5"
/usr/bin/python3 docs/plots/spd_grid_table.py --data "$OUT"

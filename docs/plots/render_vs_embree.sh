#!/bin/sh
# The render comparison of a study docs/performance.md lists: the query time of `bvhlab render`
# with the default structure against -DASDS::type=embree, same settings, 1 thread, on conference,
# sibenik and teapots. The two alternate ROUNDS times per scene; printed are the medians of T_R (primary and
# shadow rays) and of the per-round ratios ours / Embree's.
#   docs/plots/render_vs_embree.sh [OUT] [ROUNDS]     (default out/render_vs_embree 3; from the repository's root)
set -eu
OUT=${1:-out/render_vs_embree}
ROUNDS=${2:-3}
mkdir -p "$OUT"
for scene in conference sibenik teapots; do
    for r in $(seq 1 "$ROUNDS"); do
        for run in "ours" "embree -DASDS::type=embree"; do
            set -- $run
            ./build/bvhlab render --scene $scene --threads 1 ${2:-} --out "$OUT/$scene-$1-$r" > "$OUT/$scene-$1-$r.log" 2>&1 ||
                { echo "render of $scene ($1) failed: $OUT/$scene-$1-$r.log" >&2; exit 1; }
        done
    done
done
/usr/bin/python3 - "$OUT" "$ROUNDS" <<'PY'
import json, statistics, sys
out, rounds = sys.argv[1], int(sys.argv[2])
for scene in ("conference", "sibenik", "teapots"):
    line = [f"{scene:<11}"]
    for kind in ("primary", "shadow"):
        ours = [json.load(open(f"{out}/{scene}-ours-{r}.json"))[kind]["t_r_us"] for r in range(1, rounds + 1)]
        embree = [json.load(open(f"{out}/{scene}-embree-{r}.json"))[kind]["t_r_us"] for r in range(1, rounds + 1)]
        ratio = statistics.median(o / e for o, e in zip(ours, embree))
        line.append(f"{kind} {statistics.median(ours):.3f} us / embree {statistics.median(embree):.3f} us = {ratio:.2f}")
    print("   ".join(line))
PY

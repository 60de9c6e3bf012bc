#!/bin/sh
# The instruction-count yardstick of docs/performance.md: instructions and simulated branch mispredicts per query,
# counted by valgrind's cachegrind instead of timed, so that no noise moves them. For each scene and
# kind, SMALL and LARGE of the bench's rays (`bvhlab rays`) are taken from all over the image
# (cut_rays below), and each structure answers both files under `valgrind --tool=cachegrind --branch-sim=yes` (`bvhlab
# raycast`, 1 thread, BVH::isa=avx2: valgrind runs no AVX-512, and Embree picks its AVX2 kernels
# under it; BVH::epoMaxTriangles=0: no EPO statistics after the build, half the run time under
# valgrind; without --count raycast's queries count nothing, the form that bvhlab times). Per query = (count of LARGE - count of SMALL) / (LARGE - SMALL): loading the scene
# and building cancel. Shadow and incoherent rays are any-hit queries (raycast --any), as in the
# bench. Writes OUT/counts.csv (and each run's log in OUT/logs) and prints a Markdown table,
# ours / Embree's beside each structure that is not Embree.
#   docs/plots/count_instructions.sh BUILD OUT [STRUCTURE ...]        (from the repository's root)
# BUILD: a build folder configured with -DBVHLAB_NATIVE=OFF. STRUCTURE: an ASDS::type and -D keys
# as one word, e.g. "sahbvh8 -DBVH::packetFallback=8" (values without spaces); default: "default"
# (ASDS::type as env/global.env leaves it) and embree. `default` as a scene likewise means no
# --scene (the embedded scene). Environment: SCENES (default "conference sibenik teapots", names
# as `bvhlab rays --scene` takes them), KINDS (default "primary shadow incoherent"), SMALL and
# LARGE (default 20000 60000; multiples of 200).
set -euf
[ $# -ge 2 ] || { sed -n '2,/^[^#]/s/^# \{0,1\}//p' "$0" >&2; exit 2; }
BUILD=$1 OUT=$2
shift 2
[ $# -gt 0 ] || set -- default embree
SCENES=${SCENES:-conference sibenik teapots}
KINDS=${KINDS:-primary shadow incoherent}
SMALL=${SMALL:-20000} LARGE=${LARGE:-60000}
BLOCK=200  # consecutive rays kept together by cut_rays: whole packets of 8, a quarter of an 800-pixel row
[ "$SMALL" -gt 0 ] && [ "$SMALL" -lt "$LARGE" ] && [ $((SMALL % BLOCK)) -eq 0 ] && [ $((LARGE % BLOCK)) -eq 0 ] ||
    { echo "SMALL ($SMALL) and LARGE ($LARGE) must be multiples of $BLOCK, 0 < SMALL < LARGE" >&2; exit 2; }
# -march=native puts the build machine's instructions everywhere (AVX-512 on many), which valgrind
# cannot run, and would make the counts the build machine's rather than the code's.
grep -q '^BVHLAB_NATIVE:BOOL=OFF$' "$BUILD/CMakeCache.txt" ||
    { echo "$BUILD is not configured with -DBVHLAB_NATIVE=OFF (valgrind runs no AVX-512, and counts must not depend on the build machine)" >&2; exit 2; }
command -v valgrind > /dev/null || { echo "valgrind is not installed (Debian: apt-get install valgrind)" >&2; exit 2; }
mkdir -p "$OUT/rays" "$OUT/logs"
CSV=$OUT/counts.csv
echo "scene,kind,structure,accel,small,large,instructions_small,instructions_large,mispredicts_small,mispredicts_large,instructions_per_query,mispredicts_per_query" > "$CSV"

# SMALL and LARGE rays of a BVHRAYS1 file (docs/file-formats.md) in blocks of BLOCK consecutive
# rays spread evenly over the file, SMALL's blocks among LARGE's: their difference is a sample of
# the whole image. The first rays alone would be its top rows (teapots': mostly misses).
cut_rays() {
    /usr/bin/python3 - "$@" <<'PY'
import struct, sys
src, B, small, large, dst_small, dst_large = sys.argv[1], *map(int, sys.argv[2:5]), sys.argv[5], sys.argv[6]
with open(src, "rb") as f:
    magic, count = struct.unpack("<8sQ", f.read(16))
    rays = f.read()
if magic != b"BVHRAYS1" or count < large:
    sys.exit(f"{src}: not a BVHRAYS1 file of at least {large} rays ({count})")
nl, ns = large // B, small // B
picked = [i * (count // B) // nl for i in range(nl)]
for dst, chosen in ((dst_small, [picked[j * nl // ns] for j in range(ns)]), (dst_large, picked)):
    with open(dst, "wb") as f:
        f.write(struct.pack("<8sQ", magic, len(chosen) * B) + b"".join(rays[32 * B * b : 32 * B * (b + 1)] for b in chosen))
PY
}

# The number after LABEL in valgrind's summary, without its commas.
summary() { sed -n "s/^==[0-9]*== $1 *\([0-9,]*\).*/\1/p" "$2" | tr -d ,; }

for scene in $SCENES; do
    name=$(basename "$scene") && name=${name%%.*}
    scene_arg="--scene $scene" && [ "$scene" != default ] || scene_arg=""
    for kind in $KINDS; do
        any="" && [ "$kind" = primary ] || any="--any"
        all=$OUT/rays/$name.$kind.rays
        nice -n 19 "$BUILD/bvhlab" rays $scene_arg --kind "$kind" --out "$all" > "$OUT/logs/$name.$kind.rays.log" 2>&1 ||
            { echo "bvhlab rays failed: $OUT/logs/$name.$kind.rays.log" >&2; exit 1; }
        cut_rays "$all" "$BLOCK" "$SMALL" "$LARGE" "$OUT/rays/$name.$kind.$SMALL.rays" "$OUT/rays/$name.$kind.$LARGE.rays"
        rm "$all"
        for structure in "$@"; do
            type=${structure%% *} && keys=${structure#"$type"}
            type_arg="-DASDS::type=$type" && [ "$type" != default ] || type_arg=""
            label=$(printf '%s' "$structure" | tr -c 'A-Za-z0-9._=-' _)
            for n in "$SMALL" "$LARGE"; do
                log=$OUT/logs/$name.$kind.$label.$n.log
                nice -n 19 valgrind --tool=cachegrind --cache-sim=no --branch-sim=yes --cachegrind-out-file=/dev/null \
                    "$BUILD/bvhlab" raycast $scene_arg --rays "$OUT/rays/$name.$kind.$n.rays" --out "$OUT/hits" \
                    --threads 1 -DBVH::isa=avx2 -DBVH::epoMaxTriangles=0 $any $type_arg $keys > "$log" 2>&1 ||
                    { echo "raycast under valgrind failed: $log" >&2; exit 1; }
                # The run answered all n rays (raycast prints "NAME closest-hit queries: n ...").
                grep -q " queries: $n " "$log" || { echo "$log: not $n queries" >&2; exit 1; }
            done
            small=$OUT/logs/$name.$kind.$label.$SMALL.log large=$OUT/logs/$name.$kind.$label.$LARGE.log
            accel=$(sed -n 's/^\([^ ]*\) [a-z-]* queries: .*/\1/p' "$large")
            is=$(summary 'I *refs:' "$small") il=$(summary 'I *refs:' "$large")
            ms=$(summary 'Mispredicts:' "$small") ml=$(summary 'Mispredicts:' "$large")
            [ -n "$accel" ] && [ -n "$is" ] && [ -n "$il" ] && [ -n "$ms" ] && [ -n "$ml" ] ||
                { echo "$small, $large: no accelerator name or counts found (has valgrind's summary changed?)" >&2; exit 1; }
            echo "$name,$kind,\"$structure\",$accel,$SMALL,$LARGE,$is,$il,$ms,$ml,$(awk -v a="$is" -v b="$il" -v c="$ms" -v d="$ml" \
                -v n=$((LARGE - SMALL)) 'BEGIN { printf "%.2f,%.3f", (b - a) / n, (d - c) / n }')" >> "$CSV"
            echo "$name $kind $structure: $(tail -n 1 "$CSV" | cut -d, -f11-12 | tr , /) per query" >&2
        done
    done
done
rm -f "$OUT/hits"

/usr/bin/python3 - "$CSV" <<'PY'
import csv, math, sys
rows = list(csv.DictReader(open(sys.argv[1])))
scenes = list(dict.fromkeys(r["scene"] for r in rows))
kinds = list(dict.fromkeys(r["kind"] for r in rows))
structures = list(dict.fromkeys(r["structure"] for r in rows))
at = {(r["scene"], r["kind"], r["structure"]): r for r in rows}
label = {r["structure"]: r["structure"] if r["structure"].startswith(r["accel"]) else f'{r["structure"]} ({r["accel"]})'
         for r in rows}
embree = next((r["structure"] for r in rows if r["accel"] == "embree"), None)
pq = lambda r: (float(r["instructions_per_query"]), float(r["mispredicts_per_query"]))

def ratios(scene, kind, s):
    (i, m), (ei, em) = pq(at[scene, kind, s]), pq(at[scene, kind, embree])
    return i / ei, m / em if em else math.nan

print("| scene | structure | " + " | ".join(f"{k}: instructions / mispredicts" for k in kinds) + " |")
print("|---|---|" + "---:|" * len(kinds))
for scene in scenes:
    for s in structures:
        cells = []
        for kind in kinds:
            i, m = pq(at[scene, kind, s])
            cell = f"{i:.0f} / {m:.1f}"
            if embree and s != embree:
                cell += " ({:.2f}× / {:.2f}×)".format(*ratios(scene, kind, s))
            cells.append(cell)
        print(f"| {scene} | {label[s]} | " + " | ".join(cells) + " |")
if embree and len(scenes) > 1:
    for s in structures:
        if s == embree:
            continue
        cells = []
        for kind in kinds:
            r = [ratios(scene, kind, s) for scene in scenes]
            cells.append(" / ".join(f"{math.exp(sum(math.log(x[j]) for x in r) / len(r)):.2f}×" for j in (0, 1)))
        print(f"| geometric mean, × Embree | {label[s]} | " + " | ".join(cells) + " |")
PY

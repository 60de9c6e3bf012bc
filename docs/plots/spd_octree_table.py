"""The octree beside Havran's octree tables (docs/spd.md, "Havran's octrees"): reads the spd.json
that `bvhlab spd` wrote per scene (DATA/SCENE/spd.json, each octree run with the column of his
tables it stands beside) and prints one markdown table per method: per scene and maximum depth,
his row and ours with the differences. N_IT is tests per intersection required (IntersRequired),
as his octree tables count it.

    /usr/bin/python3 docs/plots/spd_octree_table.py --data out/spd_octree
"""
import argparse
import json
import pathlib

SCENES = ["balls", "mount", "rings", "teapot", "tetra", "tree"]
ROWS = ["N_IN", "N_V", "N_EV", "N_OIV", "N_IT", "N_TS", "N_ETS", "N_EETS"]
WHOLE = {"N_IN", "N_V", "N_EV", "N_OIV"}


def number(row, value):
    return f"{value:.0f}" if row in WHOLE else f"{value:.2f}"


def pct(ours, theirs):
    if theirs == 0:
        return "0.0 %" if ours == 0 else "n/a"
    return f"{100.0 * (ours - theirs) / theirs:+.1f} %"


def ours(accel, row):
    if row == "N_IT":
        inv = accel["invariants"]
        return accel["n_it"] * inv["AllRays"] / inv["IntersRequired"]
    if row == "N_TS":
        return accel["n_tr"]
    return accel["figures"][row]["value"]


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--data", default="out/spd_octree")
    args = parser.parse_args()
    tables = {}
    for scene in SCENES:
        path = pathlib.Path(args.data) / scene / "spd.json"
        if not path.exists():
            continue
        for accel in json.loads(path.read_text())["scenes"][0]["accels"]:
            havran = accel.get("havran")
            if havran:
                tables.setdefault(havran["table"], []).append((scene, havran, accel))
    for table in sorted(tables):
        print(f"**{table}** (ours / Havran's, difference)\n")
        print("| scene | depth | " + " | ".join(ROWS) + " |")
        print("|---|---:|" + "---:|" * len(ROWS))
        for scene, havran, accel in tables[table]:
            cells = []
            for row in ROWS:
                mine, theirs = ours(accel, row), havran["values"][row]
                cells.append(f"{number(row, mine)} / {number(row, theirs)} ({pct(mine, theirs)})")
            print(f"| {scene} | {havran['max_depth']} | " + " | ".join(cells) + " |")
        print()


if __name__ == "__main__":
    main()

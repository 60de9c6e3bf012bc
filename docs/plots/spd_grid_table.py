"""The grid beside Havran's uniform grid (docs/spd.md, "The uniform grid"): reads the spd.json
that `bvhlab spd` wrote per scene (DATA/SCENE/spd.json, the grid's runs as --accel lists them)
and prints one markdown row per scene and run, Havran's figures (havran_stats_grids.txt) beside.

    /usr/bin/python3 docs/plots/spd_grid_table.py --data out/spd_grid
"""
import argparse
import json
import pathlib

# Havran's uniform grid, Woo's D = 1 and D = 10 (havran_stats_grids.txt): resolution, N_V, N_EV,
# N_OIV, N_IT, N_TS.
HAVRAN = {
    "balls": [((46, 46, 3), 6348, 4208, 10240, 358.66, 5.69), ((103, 103, 7), 74263, 63393, 19966, 72.54, 12.40)],
    "mount": [((20, 20, 20), 8000, 6502, 21746, 19.01, 8.85), ((44, 44, 42), 81312, 71924, 51144, 13.17, 18.43)],
    "rings": [((21, 20, 21), 8820, 6264, 27666, 45.29, 11.78), ((44, 43, 44), 83248, 66753, 71303, 23.36, 24.51)],
    "teapot": [((28, 29, 11), 8932, 7226, 22982, 33.65, 14.98), ((61, 61, 25), 93025, 83721, 52781, 15.13, 32.50)],
    "tetra": [((16, 16, 16), 4096, 3104, 12556, 20.64, 7.43), ((35, 35, 35), 42875, 37311, 35936, 10.01, 15.97)],
    "tree": [((52, 52, 3), 8112, 5400, 11102, 727.62, 7.60), ((117, 118, 5), 69030, 55191, 22407, 246.08, 15.45)],
}


def pct(ours, theirs):
    return f"{100.0 * (ours - theirs) / theirs:+.1f} %"


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--data", default="out/spd_grid")
    args = parser.parse_args()
    print("| scene | run | resolution | N_V | N_EV | N_OIV | N_IT | N_TS |")
    print("|---|---|---|---:|---:|---:|---:|---:|")
    for scene, rows in HAVRAN.items():
        path = pathlib.Path(args.data) / scene / "spd.json"
        if not path.exists():
            continue
        accels = json.loads(path.read_text())["scenes"][0]["accels"]
        for d, (res, nv, nev, noiv, nit, nts) in zip((1, 10), rows):
            print(f"| {scene} | Havran, Woo's D = {d} | ({res[0]},{res[1]},{res[2]}) | {nv} | {nev} | {noiv} | {nit:.2f} | {nts:.2f} |")
        for a in accels:
            f = {k: v["value"] for k, v in a["figures"].items()}
            label = a["accel"].split(":", 1)[1] if ":" in a["accel"] else a["accel"]
            # The Havran row it is set beside: the same resolution, else the same density.
            if "resolution=" in label:
                res = tuple(int(x) for x in label.split("resolution=")[1].split(":")[0].split())
                havran = rows[0] if rows[0][0] == res else rows[1]
            else:
                havran = rows[0] if "density=1:" in label or label.endswith("density=1") else rows[1]
            _, nv, nev, noiv, nit, nts = havran
            print(f"| {scene} | {label} | ({int(f['res_x'])},{int(f['res_y'])},{int(f['res_z'])}) "
                  f"| {int(f['N_V'])} ({pct(f['N_V'], nv)}) | {int(f['N_EV'])} ({pct(f['N_EV'], nev)}) "
                  f"| {int(f['N_OIV'])} ({pct(f['N_OIV'], noiv)}) | {a['n_it']:.2f} ({pct(a['n_it'], nit)}) "
                  f"| {a['n_tr']:.2f} ({pct(a['n_tr'], nts)}) |")


if __name__ == "__main__":
    main()

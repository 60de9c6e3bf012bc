#!/usr/bin/python3
"""Plot of `bvhlab batch` (docs/batch.md), drawn from its results.csv.

    bvhlab plot out/batch [--out DIR]      (runs /usr/bin/python3 apps/plot/plot_batch.py --data ... --out ...)

Writes batch.png into DATA/plots unless --out names another folder: one row of panels per scene,
the build time T_B, the time per ray T_R and the intersection tests and traversal steps per ray
(N_IT, N_TR) of each structure, without and with shadow rays (its two rows in results.csv); a
figure a structure does not have (n/a) has no bar.
"""
import os

from plot_common import arguments, bar_panel, num, out_folder, read_csv  # first: it sets matplotlib's backend

import matplotlib.pyplot as plt  # noqa: E402

PANELS = [("t_b_ms", "T_B [ms]"), ("t_r_us", "T_R [µs/ray]"), ("n_it", "N_IT per ray"), ("n_tr", "N_TR per ray")]


def main():
    args = arguments(__doc__.splitlines()[0], "the folder bvhlab batch wrote (with results.csv)").parse_args()
    out = out_folder(args)
    rows = read_csv(os.path.join(args.data, "results.csv"))
    scenes = list(dict.fromkeys(r["scene"] for r in rows))
    height = max(2.0, 0.3 * max(sum(r["scene"] == s for r in rows) for s in scenes) + 1.0)
    fig, axes = plt.subplots(len(scenes), len(PANELS), figsize=(3.8 * len(PANELS), height * len(scenes)), squeeze=False)
    for axes_row, scene in zip(axes, scenes):
        measured = [r for r in rows if r["scene"] == scene]
        for ax, (key, title) in zip(axes_row, PANELS):
            labels = [r["accel"] + (" +shadows" if r["shadows"] == "true" else "") for r in measured]
            bar_panel(ax, [num(r[key]) for r in measured], labels if key == PANELS[0][0] else None, f"{scene}: {title}")
    fig.suptitle("bvhlab batch", fontsize=10)
    fig.tight_layout()
    png = os.path.join(out, "batch.png")
    fig.savefig(png, dpi=100)
    plt.close(fig)
    print(f"wrote {png}")


if __name__ == "__main__":
    main()

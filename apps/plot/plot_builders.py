#!/usr/bin/python3
"""Plots of `bvhlab tradeoff --builders` (docs/builders.md, "Builders side by side"), drawn from its CSV files.

    bvhlab plot out/builders [--out DIR]      (runs /usr/bin/python3 apps/plot/plot_builders.py --data ... --out ...)

The PNGs go to DATA/plots unless --out names another folder (created if missing). Writes
builders_pareto.png (over the scenes: geometric means of the ratios to embree-medium, one panel
per ray set) and builders_pareto_scenes.png (per scene, primary rays, absolute times). The Pareto
fronts are the command's (the pareto_* columns), not recomputed here.
"""
import math
import os

from plot_common import arguments, measured_rows, num, out_folder, plain_log_axis, read_csv  # first: it sets matplotlib's backend

import matplotlib.pyplot as plt  # noqa: E402

RAY_SETS = ["primary", "shadow", "incoherent"]


def style(config):
    """Colour per builder family, filled for the 8-wide layout, hollow for the binary one; the
    insertion pass (`+insertion`) keeps its builder's colour and fill, as a diamond."""
    builder, _, optimised = config.partition("+")
    family = builder.rstrip("8")
    colours = {"sahbvh": "tab:blue", "sbvh": "tab:green", "ploc": "tab:purple", "tdbvh": "tab:red",
               "sweepbvh": "black", "embree-low": "gold", "embree-medium": "tab:orange", "embree-high": "tab:brown"}
    wide = builder.endswith("8")
    marker = "^" if builder.startswith("embree") else "D" if optimised else "o" if wide else "s"
    filled = wide or builder.startswith("embree")
    return colours.get(family, "grey"), marker, filled


def draw(ax, points, xlabel, ylabel, title):
    """points: (config, x, y, on_front). The front is joined as a staircase."""
    for config, x, y, _ in points:
        colour, marker, filled = style(config)
        ax.scatter([x], [y], color=colour if filled else "none", edgecolors=colour, marker=marker, s=40, zorder=3)
        ax.annotate(config, (x, y), textcoords="offset points", xytext=(4, 3), fontsize=7)
    front = sorted((x, y) for _, x, y, on in points if on)
    if front:
        xs, ys = [], []
        for x, y in front:
            if xs:
                xs.append(x), ys.append(ys[-1])
            xs.append(x), ys.append(y)
        ax.plot(xs, ys, color="grey", linestyle="--", linewidth=1, zorder=2, label="Pareto front")
        ax.legend(fontsize=7, loc="upper right")
    ax.set_xscale("log")
    ax.set_yscale("log")
    for axis in (ax.xaxis, ax.yaxis):
        plain_log_axis(axis)
    ax.tick_params(which="minor", labelsize=6)
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.set_title(title, fontsize=9)
    ax.grid(True, which="both", alpha=0.3)


def main():
    args = arguments(__doc__.splitlines()[0], "folder with builders.csv and builders_summary.csv").parse_args()
    out = out_folder(args)

    summary = read_csv(os.path.join(args.data, "builders_summary.csv"))
    fig, axes = plt.subplots(1, len(RAY_SETS), figsize=(5 * len(RAY_SETS), 4.5))
    for ax, ray_set in zip(axes, RAY_SETS):
        points = [(r["config"], num(r["build_ratio_embree_medium"]), num(r[f"ratio_embree_medium_{ray_set}"]),
                   r[f"pareto_{ray_set}"] == "1") for r in summary]
        points = [p for p in points if p[1] and p[2]]
        draw(ax, points, "T_B / T_B(embree-medium)", "T_R / T_R(embree-medium)", f"{ray_set} rays")
    scenes = max(int(r["scenes"]) for r in summary)
    fig.suptitle(f"Build time against trace time, geometric means over {scenes} scenes "
                 "(hollow: binary, filled: 8-wide)", fontsize=10)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "builders_pareto.png"), dpi=110)
    plt.close(fig)

    rows = measured_rows(os.path.join(args.data, "builders.csv"))
    scene_ids = list(dict.fromkeys(r["scene"] for r in rows))
    one_thread = all(r["threads"] == "1" for r in rows)
    # T_B: wall time around build(), as the command's tables.
    build_key, trace_key = "build_ms", "t_r_primary_cpu_us" if one_thread else "t_r_primary_us"
    cols = min(3, len(scene_ids))
    rows_n = math.ceil(len(scene_ids) / cols)
    fig, axes = plt.subplots(rows_n, cols, figsize=(5 * cols, 4 * rows_n), squeeze=False)
    for ax, scene in zip(axes.flat, scene_ids):
        points = [(r["config"], num(r[build_key]), num(r[trace_key]), r["pareto_primary"] == "1")
                  for r in rows if r["scene"] == scene]
        draw(ax, [p for p in points if p[1] and p[2]], "T_B [ms]", "T_R primary [µs]", scene)
    for ax in list(axes.flat)[len(scene_ids):]:
        ax.axis("off")
    fig.suptitle("Per scene, primary rays ({})".format("T_R CPU time, 1 thread" if one_thread else "wall time"), fontsize=10)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "builders_pareto_scenes.png"), dpi=90)
    plt.close(fig)
    print(f"wrote {out}/builders_pareto.png, {out}/builders_pareto_scenes.png")


if __name__ == "__main__":
    main()

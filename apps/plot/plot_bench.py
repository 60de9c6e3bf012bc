#!/usr/bin/python3
"""Plot of `bvhlab bench` (docs/performance.md), drawn from its JSON file.

    bvhlab plot out/bench.json [--out DIR]      (runs /usr/bin/python3 apps/plot/plot_bench.py --data ... --out ...)

Writes DIR/NAME.png for DATA NAME.json (DIR: the JSON's folder unless --out names another): one
row of panels per scene, the median build time and the median time per query of each ray set,
one bar per measured row (structure, kind of query, threads), the reference rows included.
"""
import json
import os

from plot_common import arguments, bar_panel  # first: it sets matplotlib's backend

import matplotlib.pyplot as plt  # noqa: E402

RAY_SETS = ["primary", "shadow", "incoherent"]
# The rows bench adds beside the measured structures (apps/measure/bench_command.cpp), also as
# copies at an ISA of --isa-pairs (LABEL@ISA).
REFERENCE_ROWS = {"embree", "embree-robust", "nothing", "nothing-guarded", "embree-bare", "embree-batch"}


def main():
    args = arguments(__doc__.splitlines()[0], "the JSON file bvhlab bench wrote").parse_args()
    with open(args.data) as f:
        # A failed scene's row ({"scene", "failed"}: its job crashed, threw or ran out of time) has
        # no figures to draw.
        rows = [r for r in json.load(f)["rows"] if "failed" not in r]
    if not rows:
        raise SystemExit(f"{args.data}: no scene was measured (every one failed); nothing to plot")
    out = args.out or os.path.dirname(os.path.abspath(args.data))
    os.makedirs(out, exist_ok=True)
    scenes = list(dict.fromkeys(r["scene"] for r in rows))
    several_threads = len({r["threads"] for r in rows}) > 1
    panels = [("build_ms", "build [ms]")] + [(s, f"{s} rays [µs/query]") for s in RAY_SETS]
    height = max(2.0, 0.28 * max(sum(r["scene"] == s for r in rows) for s in scenes) + 1.0)
    fig, axes = plt.subplots(len(scenes), len(panels), figsize=(4.2 * len(panels), height * len(scenes)), squeeze=False)
    for axes_row, scene in zip(axes, scenes):
        measured = [r for r in rows if r["scene"] == scene]
        labels = [f'{r["accel"]} {r["queries"]}' + (f' threads={r["threads"]}' if several_threads else "") for r in measured]
        colours = ["tab:orange" if r["accel"].split("@")[0] in REFERENCE_ROWS else "tab:blue" for r in measured]
        for ax, (key, title) in zip(axes_row, panels):
            values = [r[key] if key == "build_ms" else r[key]["t_r_us"] for r in measured]
            bar_panel(ax, values, labels if key == "build_ms" else None, f"{scene}: {title}", colours)
    fig.suptitle("bvhlab bench: medians over the rounds (orange: the reference rows)", fontsize=10)
    fig.tight_layout()
    png = os.path.join(out, os.path.splitext(os.path.basename(args.data))[0] + ".png")
    fig.savefig(png, dpi=100)
    plt.close(fig)
    print(f"wrote {png}")


if __name__ == "__main__":
    main()

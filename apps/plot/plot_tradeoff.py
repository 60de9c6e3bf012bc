#!/usr/bin/python3
"""Plots of `bvhlab tradeoff` (docs/accuracy.md, "Run time against error"), drawn from its CSV files.

    bvhlab plot out/tradeoff [--out DIR]      (runs /usr/bin/python3 apps/plot/plot_tradeoff.py --data ... --out ...)

The PNGs go to DATA/plots unless --out names another folder (created if missing); `--out
docs/plots` refreshes the plots committed with the docs. Writes tradeoff_build_vs_gap.png,
tradeoff_time_to_image.png and tradeoff_error_vs_time.png, and prints the numbers the reading of
the tradeoff study (docs/accuracy.md, "Studies") quotes: the gap and relative build time per configuration, the Pareto front of
build time against SAH cost, and the ray budgets at which a slower build pays off. A run without
some of the configurations these compare (the K series of sahbvh, sweepbvh) plots what it has
and prints n/a for the rest.
"""
import math
import os
from collections import defaultdict

from plot_common import arguments, geo_mean, measured_rows, num, out_folder, plain_log_axis, read_csv  # first: it sets matplotlib's backend

import matplotlib.pyplot as plt  # noqa: E402


def style(config):
    """Colour, marker and a short label per configuration: K from a colour map, the rest fixed."""
    if config.startswith("sahbvh-K"):
        k = int(config[len("sahbvh-K"):])
        return plt.cm.viridis(min(math.log2(k) / 7.0, 1.0) * 0.9), "o", f"K={k}"
    return {"tdbvh": ("tab:red", "s", "tdbvh"), "sweepbvh": ("black", "D", "sweepbvh"),
            "embree": ("tab:orange", "^", "embree")}.get(config, ("grey", "x", config))


def main():
    parser = arguments(__doc__.splitlines()[0], "folder with tradeoff.csv and image_error.csv")
    parser.add_argument("--scenes", default="sibenik,mount", help="scenes of the error-against-time plot")
    parser.add_argument("--clock", choices=("cpu", "wall"), default="cpu",
                        help="process CPU time (default: what a loaded, shared machine cannot take away) or wall time")
    args = parser.parse_args()
    cpu = args.clock == "cpu"
    args.out = out_folder(args)

    def col(name):
        """The column of `name` (a wall-time column) for the chosen clock."""
        if not cpu:
            return name
        for suffix in ("_ms", "_us"):
            if name.endswith(suffix):
                return name[: -len(suffix)] + "_cpu" + suffix
        return name

    rows = measured_rows(os.path.join(args.data, "tradeoff.csv"))
    errors = read_csv(os.path.join(args.data, "image_error.csv"))
    scenes = list(dict.fromkeys(r["scene"] for r in rows))
    configs = list(dict.fromkeys(r["config"] for r in rows))
    by = {(r["scene"], r["config"]): r for r in rows}
    max_spp = int(rows[0]["max_spp"])
    size = f'{rows[0]["series_width"]}x{rows[0]["series_height"]}'
    sah_configs = [c for c in configs if c != "embree"]
    binned = [c for c in configs if c.startswith("sahbvh-K")]
    k16 = "sahbvh-K16" if "sahbvh-K16" in configs else binned[len(binned) // 2] if binned else None

    def ratios(c, ref, column):
        """c's column over ref's, in each scene where both have it."""
        return [num(by[s, c][column]) / num(by[s, ref][column]) for s in scenes
                if (s, c) in by and (s, ref) in by and num(by[s, c][column]) and num(by[s, ref][column])]

    def gap_point(scene, c):
        """(build time, SAH gap in %) of c in scene, None where it has no SAH gap (no sweepbvh to compare with)."""
        x, gap = num(by[scene, c][col("build_ms")]), num(by[scene, c]["sah_gap"])
        return None if x is None or gap is None else (x, 100 * gap)

    # (1) Build time against SAH gap, one panel per scene, and the summary over scenes.
    cols = 4
    panels = len(scenes) + 1
    fig, axes = plt.subplots((panels + cols - 1) // cols, cols, figsize=(4.0 * cols, 3.2 * ((panels + cols - 1) // cols)),
                             squeeze=False)
    for ax, scene in zip(axes.flat, scenes):
        series = [p for p in (gap_point(scene, c) for c in binned if (scene, c) in by) if p]
        ax.plot([x for x, _ in series], [y for _, y in series], "-", color="lightgrey", zorder=1)
        for c in sah_configs:
            point = gap_point(scene, c) if (scene, c) in by else None
            if point is None:
                continue
            colour, marker, label = style(c)
            x, y = point
            ax.scatter([x], [y], color=colour, marker=marker, zorder=2, s=28)
            ax.annotate(label.replace("K=", ""), (x, y), textcoords="offset points", xytext=(3, 3), fontsize=7)
        ax.set_xscale("log")
        plain_log_axis(ax.xaxis)
        prims = next(r["prims"] for r in rows if r["scene"] == scene)
        ax.set_title(f'{scene} ({int(prims):,} tris)', fontsize=9)
        ax.grid(True, which="both", alpha=0.3)
        ax.axhline(0, color="black", lw=0.5)
    ax = axes.flat[len(scenes)]
    for c in sah_configs:
        gaps = [num(by[s, c]["sah_gap"]) for s in scenes if (s, c) in by and by[s, c]["sah_gap"]]
        rel = geo_mean(ratios(c, k16, col("build_ms"))) if k16 else None
        if not gaps or rel is None:
            continue
        colour, marker, label = style(c)
        ax.scatter([rel], [100 * sum(gaps) / len(gaps)], color=colour, marker=marker, s=36, label=label)
        ax.annotate(label.replace("K=", ""), (rel, 100 * sum(gaps) / len(gaps)), textcoords="offset points",
                    xytext=(3, 3), fontsize=7)
    ax.set_xscale("log")
    plain_log_axis(ax.xaxis)
    ax.set_title(f"all scenes: mean gap vs geo-mean T_B / T_B({k16})" if k16 else
                 "all scenes: no K series of sahbvh to compare build times with", fontsize=9)
    ax.grid(True, which="both", alpha=0.3)
    ax.axhline(0, color="black", lw=0.5)
    for extra in list(axes.flat)[panels:]:
        extra.axis("off")
    handles = [plt.Line2D([], [], color=style(c)[0], marker=style(c)[1], ls="", label=style(c)[2]) for c in sah_configs]
    fig.legend(handles=handles, loc="lower right", ncol=2, fontsize=8, frameon=False)
    fig.supxlabel(f"build time T_B [ms, {args.clock}], 1 thread (log)")
    fig.supylabel("SAH cost above sweepbvh [%]")
    fig.suptitle("The approximation's error against its build time: sahbvh with K bins, tdbvh, sweepbvh")
    fig.tight_layout()
    fig.savefig(os.path.join(args.out, "tradeoff_build_vs_gap.png"), dpi=110)
    plt.close(fig)

    # (2) Time to image (T_B + render) at 1 and max spp, relative to embree per scene, geometric mean.
    fig, ax = plt.subplots(figsize=(10, 4.2))
    width = 0.38
    for i, (column, spp) in enumerate(((col("time_to_image_1spp_ms"), 1), (col("time_to_image_max_ms"), max_spp))):
        means, spreads = [], []
        for c in configs:
            to_embree = ratios(c, "embree", column)
            means.append(geo_mean(to_embree) or math.nan)
            spreads.append(to_embree)
        xs = [j + (i - 0.5) * width for j in range(len(configs))]
        ax.bar(xs, means, width, label=f"{spp} spp", color=["tab:blue", "tab:green"][i], alpha=0.8)
        for x, per_scene in zip(xs, spreads):
            ax.scatter([x] * len(per_scene), per_scene, color="black", s=5, zorder=3)
    ax.axhline(1, color="tab:orange", lw=1)
    ax.set_yscale("log")
    plain_log_axis(ax.yaxis)
    ax.set_xticks(range(len(configs)))
    ax.set_xticklabels(configs, rotation=30, ha="right", fontsize=8)
    ax.set_ylabel("time to image / embree's (log)")
    ax.set_title(f"Time to image (T_B + render, {size}, 1 thread, {args.clock} time): geometric mean over {len(scenes)} "
                 "scenes; dots: each scene", fontsize=10)
    ax.grid(True, axis="y", which="both", alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(os.path.join(args.out, "tradeoff_time_to_image.png"), dpi=110)
    plt.close(fig)

    # (3) Image error against time to image as the sample count grows, for the chosen scenes.
    chosen = [s for s in args.scenes.split(",") if s in scenes] or scenes[:2]
    fig, axes = plt.subplots(1, len(chosen), figsize=(6.2 * len(chosen), 4.6), squeeze=False)
    for ax, scene in zip(axes.flat, chosen):
        series = [e for e in errors if e["scene"] == scene]
        for c in configs:
            if (scene, c) not in by:
                continue
            tb = num(by[scene, c][col("build_ms")])
            xs = [(tb + num(e[("render_cpu_ms_" if cpu else "render_ms_") + c])) / 1000 for e in series]
            ys = [num(e["rmse"]) for e in series]
            colour, marker, label = style(c)
            ax.plot(xs, ys, marker=marker, color=colour, label=label, ms=4, lw=1.2)
        for e in series if (scene, "embree") in by else []:
            ax.annotate(e["spp"], (num(by[scene, "embree"][col("build_ms")]) / 1000 + num(e["render_cpu_ms_embree" if cpu else "render_ms_embree"]) / 1000,
                                   num(e["rmse"])), textcoords="offset points", xytext=(-4, -11), fontsize=7,
                        color="tab:orange")
        ax.set_xscale("log")
        ax.set_yscale("log")
        plain_log_axis(ax.xaxis)
        plain_log_axis(ax.yaxis)
        ax.set_title(f'{scene}: RMSE vs a {rows[0]["series_width"]}x{rows[0]["series_height"]} reference; '
                     f'points at 1, 2, ..., {max_spp} spp', fontsize=9)
        ax.set_xlabel(f"time to image: T_B + render [s, {args.clock}], 1 thread (log)")
        ax.set_ylabel("RMSE, linear RGB clamped to [0, 1] (log)")
        ax.grid(True, which="both", alpha=0.3)
    axes.flat[-1].legend(fontsize=7, ncol=2)
    fig.tight_layout()
    fig.savefig(os.path.join(args.out, "tradeoff_error_vs_time.png"), dpi=110)
    plt.close(fig)

    # The numbers the reading quotes.
    def shown(value, width):
        return f"{value:{width}.2f}" if value is not None else f"{'n/a':>{width}}"

    relative_build = "T_B/" + (k16.removeprefix("sahbvh-") if k16 else "K16")
    print(f"{'config':<12} {'gap mean %':>10} {'gap max %':>10} {relative_build:>8} {'T_R prim/sweep':>14} "
          f"{'image 1/embree':>14} {'image max/embree':>16}")
    for c in configs:
        gaps = [num(by[s, c]["sah_gap"]) for s in scenes if (s, c) in by and by[s, c]["sah_gap"]]
        rel = geo_mean(ratios(c, k16, col("build_ms"))) if k16 else None
        trp = geo_mean(ratios(c, "sweepbvh", col("t_r_primary_us")))
        i1 = geo_mean(ratios(c, "embree", col("time_to_image_1spp_ms")))
        im = geo_mean(ratios(c, "embree", col("time_to_image_max_ms")))
        gap_text = f"{100 * sum(gaps) / len(gaps):10.2f} {100 * max(gaps):10.2f}" if gaps else f"{'n/a':>10} {'n/a':>10}"
        print(f"{c:<12} {gap_text} {shown(rel, 8)} {shown(trp, 14)} {shown(i1, 14)} {shown(im, 16)}")

    # Pareto front of (T_B, SAH) among our structures, per scene.
    front_count = defaultdict(int)
    print("\nPareto front of build time against SAH cost (our structures), per scene:")
    for s in scenes:
        points = [(num(by[s, c][col("build_ms")]), num(by[s, c]["sah"]), c) for c in sah_configs if (s, c) in by]
        points = [(b, a, c) for (b, a, c) in points if b is not None and a is not None]
        front = [c for (b, a, c) in points
                 if not any(b2 <= b and a2 <= a and (b2 < b or a2 < a) for (b2, a2, _) in points)]
        for c in front:
            front_count[c] += 1
        print(f"  {s:<11} {', '.join(front)}")
    print("  on the front in how many scenes:", ", ".join(f"{c} {front_count[c]}" for c in sah_configs))

    # Ray budget at which a slower build pays off: per-sample render cost from the series.
    def per_spp_ms(s, c):
        return (num(by[s, c][col("render_max_ms")]) - num(by[s, c][col("render_1spp_ms")])) / (max_spp - 1)

    pixels = int(rows[0]["series_width"]) * int(rows[0]["series_height"])
    print(f"\nBreak-even: camera rays (samples x pixels) after which the first structure's image is ready sooner"
          f" (T_B + rays x time per ray, time per ray from the {size} series):")
    pairs = [("sweepbvh", k16), (k16, "tdbvh"), ("embree", k16)]
    if "sahbvh-K32" in configs and k16 != "sahbvh-K32":
        pairs.append(("sahbvh-K32", k16))
    pairs = [(a, b) for a, b in pairs if a in configs and b in configs]
    for a, b in pairs:
        cells = []
        for s in scenes:
            if (s, a) not in by or (s, b) not in by:
                continue
            dtb = num(by[s, a][col("build_ms")]) - num(by[s, b][col("build_ms")])
            dper = per_spp_ms(s, b) - per_spp_ms(s, a)
            if dtb <= 0 and dper >= 0:
                cells.append(f"{s} always")
            elif dper <= 0:
                cells.append(f"{s} never")
            else:
                rays = dtb / dper * pixels
                text = f"{rays / 1e9:.1f}G" if rays >= 1e9 else f"{rays / 1e6:.0f}M" if rays >= 1e7 else f"{rays / 1e6:.2g}M"
                cells.append(f"{s} {text}")
        print(f"  {a} over {b}: " + ", ".join(cells))


if __name__ == "__main__":
    main()

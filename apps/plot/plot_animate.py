#!/usr/bin/python3
"""Plots of `bvhlab animate` (docs/animation.md), drawn from its animate.json.

    bvhlab plot out/animate [--out DIR]      (runs /usr/bin/python3 apps/plot/plot_animate.py --data ... --out ...)

DATA is the folder that holds animate.json (the PNG files go to DATA/plots) or the file itself
(they go beside it); --out names another folder. Writes NAME_cost.png for NAME.json: per measured
frame and contender, T_update, T_R of the primary and shadow rays, and their sum; and
NAME_sah.png: each contender's SAH over its first frame's, for those that report a SAH (Embree's
do not). Both mark the frames where a contender rebuilt. A contender that failed or was skipped
(it cannot run its policy) is left out.
"""
import json
import os

from plot_common import arguments, plain_log_axis  # first: it sets matplotlib's backend

import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.ticker import MaxNLocator  # noqa: E402

# A panel's y axis turns logarithmic when its largest value is this many times its smallest.
LOG_SPAN = 20.0


def ms(part):
    return part.get("ms") if isinstance(part, dict) else None


def series(rows, value):
    """(frames, values) of the rows where `value(row)` is a number."""
    points = [(r["frame"], value(r)) for r in rows]
    points = [(f, v) for f, v in points if v is not None]
    return [f for f, _ in points], [v for _, v in points]


def trace_ms(row):
    parts = [ms(row.get("primary")), ms(row.get("shadow"))]
    return None if None in parts else sum(parts)


def total_ms(row):
    trace = trace_ms(row)
    return None if trace is None or row.get("update_ms") is None else row["update_ms"] + trace


def rebuilt(rows):
    """The rows after the first where the contender rebuilt its structure."""
    return [r for r in rows[1:] if r.get("action") in ("rebuild", "build")]


def styles(contenders):
    """A colour per contender, our structures solid, Embree's dashed."""
    colours = plt.cm.tab10.colors
    return {c["label"]: (colours[i % len(colours)], "--" if c.get("embree") else "-") for i, c in enumerate(contenders)}


def draw(ax, contenders, style, value):
    """A line per contender of `value(contender, row)` over the frames, a dot where it rebuilt; a
    logarithmic y axis where the values span more than LOG_SPAN."""
    values = []
    for c in contenders:
        colour, dash = style[c["label"]]
        xs, ys = series(c["rows"], lambda r: value(c, r))
        ax.plot(xs, ys, dash, color=colour, lw=1.2, label=c["label"])
        mx, my = series(rebuilt(c["rows"]), lambda r: value(c, r))
        ax.plot(mx, my, "o", color=colour, ms=4)
        values += ys
    positive = [v for v in values if v > 0]
    if positive and max(positive) > LOG_SPAN * min(positive):
        ax.set_yscale("log", nonpositive="mask")  # a zero (an update with nothing to do) has no place on it
        plain_log_axis(ax.yaxis)
    ax.grid(True, which="both", alpha=0.3)
    ax.set_xlabel("frame")
    ax.xaxis.set_major_locator(MaxNLocator(integer=True))


def sah(row):
    return row.get("sah") if isinstance(row.get("sah"), (int, float)) else None


def sah_drift(contender, row):
    """The SAH of a frame over the contender's first frame's."""
    return None if sah(row) is None else sah(row) / sah(contender["rows"][0])


def main():
    args = arguments(__doc__.splitlines()[0], "the folder bvhlab animate wrote (with animate.json), or that file").parse_args()
    folder = os.path.isdir(args.data)
    path = os.path.join(args.data, "animate.json") if folder else args.data
    with open(path) as f:
        results = json.load(f)
    contenders = [c for c in results["contenders"] if "failed" not in c and "skipped" not in c and c.get("rows")]
    if not contenders:
        raise SystemExit(f"{path}: no contender was measured (every one failed or was skipped); nothing to plot")
    out = args.out or (os.path.join(args.data, "plots") if folder else os.path.dirname(os.path.abspath(path)))
    os.makedirs(out, exist_ok=True)
    name = os.path.splitext(os.path.basename(path))[0]
    scene = results.get("scene", {}).get("name", "?")
    setting = f'{scene}, threads: {results.get("threads", "?")}'
    style = styles(contenders)

    fig, axes = plt.subplots(1, 3, figsize=(15, 4.6))
    for ax, (value, title) in zip(axes, [(lambda c, r: r.get("update_ms"), "T_update [ms]"),
                                         (lambda c, r: trace_ms(r), "T_R, primary + shadow rays [ms]"),
                                         (lambda c, r: total_ms(r), "update + trace [ms]")]):
        draw(ax, contenders, style, value)
        ax.set_title(title, fontsize=9)
    handles, labels = axes[0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="lower center", ncol=min(len(labels), 4), fontsize=7, frameon=False)
    fig.suptitle(f"bvhlab animate: cost per frame ({setting}); dots: rebuilds; dashed: Embree", fontsize=10)
    fig.tight_layout(rect=(0, 0.04 * ((len(labels) + 3) // 4), 1, 1))
    cost = os.path.join(out, name + "_cost.png")
    fig.savefig(cost, dpi=100)
    plt.close(fig)

    fig, ax = plt.subplots(figsize=(8, 4.6))
    with_sah = [c for c in contenders if (sah(c["rows"][0]) or 0) > 0]
    if with_sah:
        draw(ax, with_sah, style, sah_drift)
        ax.axhline(1, color="black", lw=0.5)
        ax.legend(fontsize=7)
    else:
        ax.text(0.5, 0.5, "no contender reports its SAH (Embree's do not)", ha="center", va="center",
                transform=ax.transAxes)
    ax.set_ylabel("SAH / first frame's SAH")
    ax.set_title(f"bvhlab animate: SAH drift ({setting}); dots: rebuilds", fontsize=10)
    fig.tight_layout()
    sah_png = os.path.join(out, name + "_sah.png")
    fig.savefig(sah_png, dpi=100)
    plt.close(fig)
    print(f"wrote {cost} and {sah_png}")


if __name__ == "__main__":
    main()

"""What the plot scripts of `bvhlab plot` share (apps/plot/): reading bvhlab's CSV files, their
empty cells (n/a) as None, geometric means, log axes labelled in plain numbers, and the command
line every script takes: --data (the output to plot) and --out (the folder of the PNG files)."""
import argparse
import csv
import math
import os

import matplotlib

matplotlib.use("Agg")
from matplotlib.ticker import FuncFormatter  # noqa: E402

PLAIN = FuncFormatter(lambda v, _: f"{v:g}")


def arguments(description, data_help):
    """--data and --out (default: DATA/plots for a folder, created if missing)."""
    parser = argparse.ArgumentParser(description=description)
    parser.add_argument("--data", required=True, help=data_help)
    parser.add_argument("--out", help="folder for the PNG files (default: DATA/plots; created if missing)")
    return parser


def out_folder(args):
    out = args.out or os.path.join(args.data, "plots")
    os.makedirs(out, exist_ok=True)
    return out


def read_csv(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def measured_rows(path):
    """The rows of a tradeoff's CSV file whose configuration was measured: a failed one (it crashed,
    threw or ran out of time; its reason in the column "failed") has no figures to draw. Ends the
    script with a message when no row is left."""
    rows = [r for r in read_csv(path) if not r.get("failed")]
    if not rows:
        raise SystemExit(f"{path}: no configuration was measured (every row failed); nothing to plot")
    return rows


def num(text):
    """A cell as a number; an empty cell (not measured, n/a) as None."""
    return float(text) if text not in ("", None) else None


def geo_mean(values):
    """The geometric mean of the positive values, None when there is none."""
    values = [v for v in values if v is not None and v > 0]
    return math.exp(sum(math.log(v) for v in values) / len(values)) if values else None


def plain_log_axis(axis):
    """Log-scale tick labels as plain numbers (0.5, 2, 300), not powers of ten."""
    axis.set_major_formatter(PLAIN)
    axis.set_minor_formatter(FuncFormatter(lambda v, _: f"{v:g}" if f"{v:.0e}"[0] in "25" else ""))


def bar_panel(ax, values, labels, title, colours=None):
    """Horizontal bars, top to bottom, each with its value written beside it; a value that is None
    (n/a) has no bar. `labels` name the bars (None: no tick labels, as beside a panel that names them)."""
    ax.barh(range(len(values)), [v if v is not None else float("nan") for v in values], color=colours)
    for y, v in enumerate(values):
        ax.annotate("n/a" if v is None else f"{v:.3g}", (v or 0, y), textcoords="offset points", xytext=(3, -3),
                    fontsize=7)
    ax.set_yticks(range(len(values)))
    ax.set_yticklabels(labels or [], fontsize=7)
    ax.invert_yaxis()
    ax.margins(x=0.25)
    ax.set_title(title, fontsize=9)
    ax.grid(True, axis="x", alpha=0.3)

#!/usr/bin/python3
"""Figure of a campaign (flexgait campaign): campaign.png beside campaign.csv.

1-D grid: each numeric metric against the axis (one panel each). 2-D grid: a heat map per numeric
metric, and a discrete map per categorical one (gait, fell, converged, ...), the first axis
vertical. Extra axes (3-D and more) are split into one figure per combination of their values:
campaign_<key>=<value>...png. Metrics that do not vary are left out.

Usage: plot_campaign.py RUN_DIR   (reads RUN_DIR/campaign.csv and the axis keys from its header
before the first metric, i.e. the columns of RUN_DIR/config.yaml's "--grid" lines)
"""
import itertools
import math
import os
import re
import sys

from flexgait_plotting import read_rows, save_atomic
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

MAX_PANELS = 16  # keep a figure readable: the first categorical, then numeric metrics that vary


def axis_keys(run_dir):
    keys = []
    with open(os.path.join(run_dir, "config.yaml"), encoding="utf-8") as f:
        for line in f:
            m = re.match(r"^#   --grid ([^=]+)=", line)
            if m:
                keys.append(m.group(1))
    return keys


def number(text):
    try:
        v = float(text)
    except ValueError:
        return None
    return v if math.isfinite(v) else None


def split_metrics(rows, metrics):
    numeric, categorical = [], []
    for m in metrics:
        values = [r[m] for r in rows]
        if len(set(values)) <= 1 or any(";" in v for v in values):
            continue
        if all(number(v) is not None or v == "" for v in values) and any(v != "" for v in values):
            numeric.append(m)
        else:
            categorical.append(m)
    return numeric, categorical


def ordered(values):
    seen = []
    for v in values:
        if v not in seen:
            seen.append(v)
    return seen


def figure(rows, axes, metrics, run_dir, name, title):
    numeric, categorical = split_metrics(rows, metrics)
    panels = (categorical + numeric)[:MAX_PANELS]  # the discrete maps (fell, gait, ...) first
    if not panels:
        return
    cols = min(3, len(panels))
    nrows = math.ceil(len(panels) / cols)
    fig, grid = plt.subplots(nrows, cols, figsize=(5 * cols, 3.6 * nrows), squeeze=False, constrained_layout=True)
    fig.suptitle(title)
    for ax in grid.flat[len(panels):]:
        ax.axis("off")
    xs = ordered(r[axes[0]] for r in rows)
    ys = ordered(r[axes[1]] for r in rows) if len(axes) > 1 else None
    for ax, m in zip(grid.flat, panels):
        ax.set_title(m, fontsize=9)
        if m in numeric:
            if ys is None:
                pts = [(number(r[axes[0]]), number(r[m])) for r in rows]
                if all(p[0] is not None for p in pts):
                    ax.plot([p[0] for p in pts], [np.nan if p[1] is None else p[1] for p in pts], "o-")
                else:
                    ax.plot(range(len(pts)), [np.nan if p[1] is None else p[1] for p in pts], "o-")
                    ax.set_xticks(range(len(pts)), xs)
                ax.set_xlabel(axes[0])
                continue
            z = np.full((len(ys), len(xs)), np.nan)
            for r in rows:
                v = number(r[m])
                z[ys.index(r[axes[1]]), xs.index(r[axes[0]])] = np.nan if v is None else v
            im = ax.imshow(z, origin="lower", aspect="auto", interpolation="nearest")
            fig.colorbar(im, ax=ax)
        else:
            labels = ordered(r[m] or "-" for r in rows)
            if ys is None:
                ax.scatter(range(len(rows)), [labels.index(r[m] or "-") for r in rows])
                ax.set_yticks(range(len(labels)), labels, fontsize=7)
                ax.set_xticks(range(len(xs)), xs, rotation=45, fontsize=7)
                ax.set_xlabel(axes[0])
                continue
            z = np.full((len(ys), len(xs)), np.nan)
            for r in rows:
                z[ys.index(r[axes[1]]), xs.index(r[axes[0]])] = labels.index(r[m] or "-")
            cmap = plt.get_cmap("tab10", len(labels))
            im = ax.imshow(z, origin="lower", aspect="auto", interpolation="nearest", cmap=cmap,
                           vmin=-0.5, vmax=len(labels) - 0.5)
            bar = fig.colorbar(im, ax=ax, ticks=range(len(labels)))
            bar.ax.set_yticklabels([lab[:24] for lab in labels], fontsize=7)
        ax.set_xticks(range(len(xs)), xs, rotation=45, fontsize=7)
        ax.set_yticks(range(len(ys)), ys, fontsize=7)
        ax.set_xlabel(axes[0])
        ax.set_ylabel(axes[1])
    save_atomic(fig, run_dir, name)
    plt.close(fig)


def main(run_dir):
    rows = read_rows(os.path.join(run_dir, "campaign.csv"))
    if not rows:
        return
    axes = axis_keys(run_dir)
    metrics = [c for c in rows[0].keys() if c not in axes and c != "index"]
    fixed = axes[2:]
    for combo in itertools.product(*[ordered(r[k] for r in rows) for k in fixed]):
        subset = [r for r in rows if all(r[k] == v for k, v in zip(fixed, combo))]
        suffix = "".join(f"_{k}={v}" for k, v in zip(fixed, combo))
        title = "campaign" + "".join(f", {k} = {v}" for k, v in zip(fixed, combo))
        figure(subset, axes[:2], metrics, run_dir, f"campaign{suffix}.png", title)


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])

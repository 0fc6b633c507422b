#!/usr/bin/python3
"""Figure of a campaign (flexgait campaign): campaign.png beside campaign.csv.

1-D grid: each numeric metric against the axis (one panel each). 2-D grid: a heat map per numeric
metric, the second axis vertical. Extra axes (3-D and more) are split into one figure per
combination of their values: campaign_<key>=<value>...png. By default only the numeric metrics
that vary are drawn (a spread below 1e-9 of their size is round-off, not variation); categorical
ones (gait, fell, converged, ...) are drawn as discrete maps when named with --metrics. Every axis
and colour bar says its unit (from `flexgait schema`), ticks have at most 4 significant digits,
and the title names the experiment and its axes.

With --random keys (a `sample` axis) campaign.png is not drawn: a map per random draw means
nothing; reduce over `sample` instead. With --reduced K1,K2 also reduced.png from reduced.csv (flexgait campaign --reduce), drawn the same
way over the axes not reduced over; a chosen metric M stands there as M_fraction or M_mean.

With --metrics M1,M2,... only those metrics are drawn, in that order (even if they do not vary),
and a third axis becomes the rows of the one figure campaign.png (one row per value, a shared
colour scale and category colours per metric, the value written in each cell of a small map), so
its values compare at a glance: e.g. the walking envelope's `fell` and `pelvis_roll_error_max`
with control.compensation off against both. Axes beyond the third still split the figure.

Usage: plot_campaign.py RUN_DIR [--metrics M1,M2,...] [--reduced K1,...]   (reads RUN_DIR/campaign.csv, the
axis keys from RUN_DIR/config.yaml's "--grid" lines and the drawn keys from its "--random" lines)
"""
import argparse
import itertools
import math
import os
import re
import sys

from flexgait_plotting import load_schema, read_rows, save_atomic
import matplotlib.pyplot as plt  # noqa: E402
import matplotlib.ticker as ticker  # noqa: E402
import numpy as np  # noqa: E402

MAX_PANELS = 16  # keep a figure readable: the first categorical, then numeric metrics that vary
MAX_ANNOTATED_CELLS = 120  # write each cell's value into maps up to this size (--metrics)
ROUND_OFF = 1e-9  # a metric whose spread is below this fraction of its size does not vary
TICKS = ticker.FuncFormatter(lambda v, _: f"{v:.4g}")  # at most 4 significant digits, no offset


class FourDigitLocator(ticker.MaxNLocator):
    """Matplotlib's nice ticks, spaced no closer than a value's 4th significant digit (so that
    TICKS writes every tick differently); a range narrower than that gets the ticks it holds."""

    def __init__(self):
        super().__init__(nbins=5)

    def tick_values(self, vmin, vmax):
        ticks = super().tick_values(vmin, vmax)
        if len({f"{t:.4g}" for t in ticks}) == len(ticks):
            return ticks
        size = max(abs(vmin), abs(vmax))
        step = 10.0 ** (math.floor(math.log10(size)) - 3)
        for k in (1, 2, 5, 10, 20, 50):
            if (vmax - vmin) / (k * step) <= 6:
                break
        return ticker.MultipleLocator(k * step).tick_values(vmin, vmax)
UNITS = {}  # name -> unit of every configuration key and summary field (units_of fills it)


def units_of(run_dir):
    """Every configuration key's and summary field's unit, from `flexgait schema` ({} without it)."""
    try:
        _, schema = load_schema(run_dir)
    except Exception:  # noqa: BLE001 -- a figure without units rather than none
        return {}
    units = {}
    for keys in schema.get("configurations", {}).values():
        for k in keys:
            units.setdefault(k["key"], k.get("unit", ""))
    for result in schema.get("results", {}).values():
        for f in result.get("fields", []):
            units.setdefault(f["key"], f.get("unit", ""))
    return units


def labelled(name):
    """`name [unit]`, or the name alone when it has no unit."""
    unit = UNITS.get(name, "")
    return f"{name} [{unit}]" if unit else name


def tick_text(value):
    """A grid value as a tick label: numbers with at most 4 significant digits."""
    v = number(value)
    return f"{v:.4g}" if v is not None else value


def header_keys(run_dir, option):
    """The keys of config.yaml's "#   --grid KEY=..." (or --random) header lines, in order."""
    keys = []
    with open(os.path.join(run_dir, "config.yaml"), encoding="utf-8") as f:
        for line in f:
            m = re.match(rf"^#   --{option} ([^=]+)=", line)
            if m:
                keys.append(m.group(1))
    return keys


def number(text):
    try:
        v = float(text)
    except ValueError:
        return None
    return v if math.isfinite(v) else None


def is_numeric(values):
    return all(number(v) is not None or v == "" for v in values) and any(v != "" for v in values)


def varies(values, numeric):
    """Whether the cells differ by more than round-off (numbers) or at all (text)."""
    if not numeric:
        return len(set(values)) > 1
    xs = [x for x in (number(v) for v in values) if x is not None]  # points without a value: blank cells
    return bool(xs) and max(xs) - min(xs) > ROUND_OFF * max(abs(x) for x in xs)


def split_metrics(rows, metrics, keep_constant=False):
    """(numeric, categorical) metrics to draw: with keep_constant (chosen metrics) all of them,
    else only the numeric ones that vary."""
    numeric, categorical = [], []
    for m in metrics:
        values = [r[m] for r in rows]
        if any(";" in v for v in values):
            continue
        is_num = is_numeric(values)
        if keep_constant:
            (numeric if is_num else categorical).append(m)
        elif is_num and varies(values, True):
            numeric.append(m)
    return numeric, categorical


def ordered(values):
    seen = []
    for v in values:
        if v not in seen:
            seen.append(v)
    return seen


def panel(fig, ax, rows, axes, m, numeric, scale, annotate=False):
    """One metric of `rows` over `axes` (1 or 2 of them). `scale`: (vmin, vmax) of a numeric
    metric, or the category labels of a categorical one (shared across a figure's rows)."""
    xs = ordered(r[axes[0]] for r in rows)
    ys = ordered(r[axes[1]] for r in rows) if len(axes) > 1 else None
    ax.set_title(labelled(m), fontsize=9)
    if numeric:
        if ys is None:
            pts = [(number(r[axes[0]]), number(r[m])) for r in rows]
            if all(p[0] is not None for p in pts):
                ax.plot([p[0] for p in pts], [np.nan if p[1] is None else p[1] for p in pts], "o-")
                ax.xaxis.set_major_formatter(TICKS)
            else:
                ax.plot(range(len(pts)), [np.nan if p[1] is None else p[1] for p in pts], "o-")
                ax.set_xticks(range(len(pts)), [tick_text(x) for x in xs])
            ax.yaxis.set_major_locator(FourDigitLocator())
            ax.yaxis.set_major_formatter(TICKS)
            ax.set_xlabel(labelled(axes[0]))
            ax.set_ylabel(labelled(m), fontsize=8)
            return
        z = np.full((len(ys), len(xs)), np.nan)
        for r in rows:
            v = number(r[m])
            z[ys.index(r[axes[1]]), xs.index(r[axes[0]])] = np.nan if v is None else v
        vmin, vmax = scale if scale else (None, None)
        im = ax.imshow(z, origin="lower", aspect="auto", interpolation="nearest", vmin=vmin, vmax=vmax)
        fig.colorbar(im, ax=ax, ticks=FourDigitLocator(), format=TICKS, label=UNITS.get(m) or None)
        if annotate:  # dark text on the bright end of viridis, light on the dark end
            lo, hi = im.get_clim()
            for (yi, xi), v in np.ndenumerate(z):
                if not np.isnan(v):
                    bright = hi > lo and (v - lo) / (hi - lo) > 0.6
                    ax.text(xi, yi, f"{v:.3g}", ha="center", va="center", fontsize=6, color="k" if bright else "w")
    else:
        labels = scale if scale else ordered(r[m] or "-" for r in rows)
        if ys is None:
            ax.scatter(range(len(rows)), [labels.index(r[m] or "-") for r in rows])
            ax.set_yticks(range(len(labels)), labels, fontsize=7)
            ax.set_xticks(range(len(xs)), [tick_text(x) for x in xs], rotation=45, fontsize=7)
            ax.set_xlabel(labelled(axes[0]))
            return
        z = np.full((len(ys), len(xs)), np.nan)
        for r in rows:
            z[ys.index(r[axes[1]]), xs.index(r[axes[0]])] = labels.index(r[m] or "-")
        cmap = plt.get_cmap("tab10", len(labels))
        im = ax.imshow(z, origin="lower", aspect="auto", interpolation="nearest", cmap=cmap,
                       vmin=-0.5, vmax=len(labels) - 0.5)
        bar = fig.colorbar(im, ax=ax, ticks=range(len(labels)))
        bar.ax.set_yticklabels([lab[:24] for lab in labels], fontsize=7)
    ax.set_xticks(range(len(xs)), [tick_text(x) for x in xs], rotation=45, fontsize=7)
    ax.set_yticks(range(len(ys)), [tick_text(y) for y in ys], fontsize=7)
    ax.set_xlabel(labelled(axes[0]))
    ax.set_ylabel(labelled(axes[1]))


def figure(rows, axes, metrics, run_dir, name, title, chosen=False):
    numeric, categorical = split_metrics(rows, metrics, keep_constant=chosen)
    if chosen:  # as asked, in the order asked
        panels = [m for m in metrics if m in numeric or m in categorical]
    else:  # the discrete maps (fell, gait, ...) first
        panels = (categorical + numeric)[:MAX_PANELS]
    if not panels:
        return
    cols = min(3, len(panels))
    nrows = math.ceil(len(panels) / cols)
    fig, grid = plt.subplots(nrows, cols, figsize=(5 * cols, 3.6 * nrows), squeeze=False, constrained_layout=True)
    fig.suptitle(title)
    for ax in grid.flat[len(panels):]:
        ax.axis("off")
    for ax, m in zip(grid.flat, panels):
        panel(fig, ax, rows, axes, m, m in numeric, None)
    save_atomic(fig, run_dir, name)
    plt.close(fig)


def shared_scale(rows, m, numeric):
    """The colour range (numeric) or the category labels of metric m over all of `rows`."""
    if not numeric:
        return ordered(r[m] or "-" for r in rows)
    values = [v for v in (number(r[m]) for r in rows) if v is not None]
    return (min(values), max(values)) if values else None


def compare_figure(rows, axes, by, metrics, run_dir, name, title):
    """One row of panels per value of axis `by`, one column per metric, shared scales."""
    numeric = {m for m in metrics if is_numeric([r[m] for r in rows])}
    scales = {m: shared_scale(rows, m, m in numeric) for m in metrics}
    values = ordered(r[by] for r in rows)
    fig, grid = plt.subplots(len(values), len(metrics), figsize=(5 * len(metrics), 3.6 * len(values)),
                             squeeze=False, constrained_layout=True)
    fig.suptitle(title)
    for row_axes, value in zip(grid, values):
        subset = [r for r in rows if r[by] == value]
        annotate = len(subset) <= MAX_ANNOTATED_CELLS
        for ax, m in zip(row_axes, metrics):
            panel(fig, ax, subset, axes, m, m in numeric, scales[m], annotate)
            ax.set_title(f"{labelled(m)}, {by} = {tick_text(value)}", fontsize=9)
    save_atomic(fig, run_dir, name)
    plt.close(fig)


def reduced_metric(columns, m):
    """The column of reduced.csv that stands for campaign metric m: its fraction or its mean."""
    return next((c for c in (m + "_fraction", m + "_mean") if c in columns), None)


def experiment_of(run_dir):
    """The experiment named in config.yaml's first line ("# campaign of NAME (flexgait ...)")."""
    with open(os.path.join(run_dir, "config.yaml"), encoding="utf-8") as f:
        m = re.match(r"^# campaign of (\S+)", f.readline())
    return m.group(1) if m else "campaign"


def draw(rows, axes, metrics, chosen, run_dir, stem):
    """STEM.png (or STEM_<key>=<value>....png per combination of the axes beyond those drawn)."""
    by = axes[2] if chosen and len(axes) >= 3 else None
    fixed = axes[3:] if by else axes[2:]
    for combo in itertools.product(*[ordered(r[k] for r in rows) for k in fixed]):
        subset = [r for r in rows if all(r[k] == v for k, v in zip(fixed, combo))]
        suffix = "".join(f"_{k}={v}" for k, v in zip(fixed, combo))
        title = (f"{experiment_of(run_dir)}{' (reduced)' if stem == 'reduced' else ''} over "
                 + " × ".join(axes[:3] if by else axes[:2])
                 + "".join(f", {k} = {tick_text(v)}" for k, v in zip(fixed, combo)))
        if by:
            compare_figure(subset, axes[:2], by, chosen, run_dir, f"{stem}{suffix}.png", title)
        else:
            figure(subset, axes[:2], chosen or metrics, run_dir, f"{stem}{suffix}.png", title, bool(chosen))


def main(argv):
    parser = argparse.ArgumentParser(description="Draws campaign.png beside a campaign's campaign.csv.")
    parser.add_argument("run_dir")
    parser.add_argument("--metrics", help="comma-separated metrics to draw; a third axis becomes the figure's rows")
    parser.add_argument("--reduced", help="comma-separated axes reduced over in reduced.csv: also draw reduced.png "
                                          "over the other axes (each chosen metric as its fraction or mean)")
    args = parser.parse_args(argv)
    rows = read_rows(os.path.join(args.run_dir, "campaign.csv"))
    if not rows:
        return 0
    UNITS.update(units_of(args.run_dir))
    axes = header_keys(args.run_dir, "grid")
    drawn = header_keys(args.run_dir, "random")  # drawn per sample: neither axes nor metrics
    metrics = [c for c in rows[0].keys() if c not in axes and c not in drawn and c != "index"]
    chosen = args.metrics.split(",") if args.metrics else None
    if chosen:
        unknown = [m for m in chosen if m not in metrics]
        if unknown:
            print(f"plot_campaign.py: no metric {', '.join(unknown)} in campaign.csv", file=sys.stderr)
            return 2
    if not drawn:  # with random keys, a map per sample means nothing: reduce over `sample`
        draw(rows, axes, metrics, chosen, args.run_dir, "campaign")
    if args.reduced:
        kept = [k for k in axes if k not in args.reduced.split(",")]
        reduced = read_rows(os.path.join(args.run_dir, "reduced.csv"))
        if not kept or not reduced:  # one row: nothing to map
            return 0
        columns = [c for c in reduced[0].keys() if c not in kept and c != "points"]
        picked = [c for c in (reduced_metric(columns, m) for m in chosen) if c] if chosen else None
        draw(reduced, kept, columns, picked, args.run_dir, "reduced")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))

#!/usr/bin/python3
"""Figure of a rimless-wheel parameter sweep: gait, largest multiplier, speed and energy per cycle.

Usage: plot_sweep.py RUN_DIR PARAM   (reads RUN_DIR/sweep.csv; writes RUN_DIR/sweep.png atomically)
"""
import sys

from flexgait_plotting import cell, read_table, save_atomic
import matplotlib.pyplot as plt  # noqa: E402

GAIT_ORDER = ["slip", "slip-stick-slip", "slip-stick", "touchdown-stick slip-stick", "stick-slip", "stick"]


def main(run_dir, param):
    # (gait-vs-friction writes the same sweep.csv: the same columns)
    rows = read_table(run_dir, "sweep.csv", "rimless sweep")
    x = [cell(rows, r, "value", float) for r in rows]
    ok = [cell(rows, r, "converged") == "true" for r in rows]
    gaits = [cell(rows, r, "gait") if c else (cell(rows, r, "transient_gait") or "none") for r, c in zip(rows, ok)]
    order = GAIT_ORDER + sorted({g for g in gaits if g not in GAIT_ORDER})
    fig, axes = plt.subplots(4, 1, figsize=(9, 11), sharex=True, constrained_layout=True)
    ax = axes[0]
    for conv, marker, label in ((True, "o", "fixed point found"), (False, "x", "no fixed point (transient gait)")):
        xs = [xi for xi, c in zip(x, ok) if c == conv]
        ys = [order.index(g) for g, c in zip(gaits, ok) if c == conv]
        ax.scatter(xs, ys, marker=marker, label=label)
    ax.set_yticks(range(len(order)))
    ax.set_yticklabels(order)
    ax.set_title("Gait (stance-foot phases in single support)")
    ax.legend(loc="best")
    ax = axes[1]
    xs = [xi for xi, c in zip(x, ok) if c]
    found = [r for r, c in zip(rows, ok) if c]
    ax.plot(xs, [cell(rows, r, "max_multiplier", float) for r in found], "o-")
    ax.axhline(1.0, color="k", lw=0.8, ls="--")
    ax.set_ylabel("largest |multiplier|")
    ax = axes[2]
    ax.plot(xs, [cell(rows, r, "speed", float) for r in found], "o-")
    ax.set_ylabel("speed on the orbit [m/s]")
    ax = axes[3]
    ax.plot(xs, [cell(rows, r, "dissipated_per_cycle", float) for r in found], "o-")
    ax.set_ylabel("energy per step [J]")
    ax.set_xlabel(param)
    save_atomic(fig, run_dir, "sweep.png")


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.stderr.write(__doc__)
        sys.exit(2)
    main(sys.argv[1], sys.argv[2])

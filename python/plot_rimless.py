#!/usr/bin/python3
"""Figures of one rimless-wheel run: hub path, foot phases over time, energy ledger.

Usage: plot_rimless.py RUN_DIR   (reads log.csv, steps.csv; writes rimless.png atomically)
"""
import os
import sys

from flexgait_plotting import cell, column, read_table, save_atomic
import matplotlib.pyplot as plt  # noqa: E402


def main(run_dir):
    log = read_table(run_dir, "log.csv", "rimless simulate")
    steps = read_table(run_dir, "steps.csv", "rimless simulate")
    t = column(log, "t")
    fig, axes = plt.subplots(4, 1, figsize=(10, 12), constrained_layout=True)

    ax = axes[0]
    ax.plot(column(log, "x"), column(log, "y"), lw=1.2)
    ax.set_xlabel("hub x along the slope [m]")
    ax.set_ylabel("hub y [m]")
    ax.set_title("Hub path (slope frame)")

    ax = axes[1]
    colours = {"stick": "tab:green", "slip+": "tab:red", "slip-": "tab:orange"}
    legs = sorted({cell(log, r, f"leg{i}", int) for r in log for i in (1, 2, 3) if cell(log, r, f"leg{i}", int) >= 0})
    # Contiguous intervals of (leg, phase), drawn as bars.
    intervals = {}
    for i in (1, 2, 3):
        start = None
        for r0, r1 in zip(log.rows[:-1], log.rows[1:]):
            key = (cell(log, r0, f"leg{i}", int), cell(log, r0, f"phase{i}"))
            if start is None or key != start[0]:
                start = (key, cell(log, r0, "t", float))
            if key[0] >= 0 and (cell(log, r1, f"leg{i}", int), cell(log, r1, f"phase{i}")) != key or r1 is log.rows[-1]:
                if key[0] >= 0:
                    intervals.setdefault(key, []).append((start[1], cell(log, r1, "t", float) - start[1]))
                start = None
    for (leg, phase), spans in intervals.items():
        ax.broken_barh(spans, (leg - 0.3, 0.6), color=colours[phase])
    for name, c in colours.items():
        ax.plot([], [], color=c, lw=6, label=name)
    ax.set_yticks(legs)
    ax.set_ylabel("leg on the ground")
    ax.set_xlabel("t [s]")
    ax.legend(loc="upper right", ncol=3)
    gaits = [cell(steps, s, "gait") for s in steps if cell(steps, s, "complete") == "true"]
    ax.set_title("Foot phases; step gaits: " + (" ".join(gaits[-6:]) if gaits else "-"))

    ax = axes[2]
    for key, label in (("E_kinetic", "kinetic"), ("E_spring", "spring"), ("W_damp", "damper work"),
                       ("W_fric", "friction work")):
        ax.plot(t, column(log, key), label=label)
    e_total = column(log, "E_total")
    ax.plot(t, [e - e_total[0] for e in e_total], label="E(t) - E(0)")
    ax.set_ylabel("energy [J]")
    ax.set_xlabel("t [s]")
    ax.legend(loc="upper left", ncol=3)
    ax.set_title("Energy ledger")

    ax = axes[3]
    ax.plot(t, column(log, "balance"), color="k", lw=0.8)
    ax.set_ylabel("E + W_damp + W_fric - E(0) [J]")
    ax.set_xlabel("t [s]")
    ax.set_title("Energy balance residual")

    save_atomic(fig, run_dir, "rimless.png")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.stderr.write(__doc__)
        sys.exit(2)
    main(sys.argv[1])

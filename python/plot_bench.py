#!/usr/bin/python3
"""Figure of the stiffness bench (thesis Fig. 12): angle error against gravity torque, before and
after compensation.

Usage: plot_bench.py RUN_DIR   (reads bench.csv; writes bench.png atomically)
"""
import sys

from flexgait_plotting import cell, read_table, save_atomic
import matplotlib.pyplot as plt  # noqa: E402


def main(run_dir):
    rows = read_table(run_dir, "bench.csv", "humanoid bench")
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.5), constrained_layout=True)
    for ax, comp, title in ((axes[0], "false", "(a) uncompensated"), (axes[1], "true", "(b) compensated")):
        sel = [r for r in rows if cell(rows, r, "compensated") == comp]
        tau = [cell(rows, r, "gravity_torque", float) for r in sel]
        ax.plot(tau, [cell(rows, r, "error_link_minus_encoder", float) for r in sel], "o", label="link - encoder")
        ax.plot(tau, [cell(rows, r, "error_link_minus_command", float) for r in sel], "x", label="link - desired")
        ax.axhline(0, color="k", lw=0.6)
        ax.set_xlabel("gravity torque [Nm]")
        ax.set_ylabel("angle error [rad]")
        ax.set_title(title)
        ax.legend()
    save_atomic(fig, run_dir, "bench.png")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.stderr.write(__doc__)
        sys.exit(2)
    main(sys.argv[1])

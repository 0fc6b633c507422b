#!/usr/bin/python3
"""Figures of a walk: ZMP x/y against the reference, COM, pelvis roll/pitch (IMU), footprints.

Usage: plot_walk.py RUN_DIR   (reads log.csv and footsteps.csv; writes walk.png atomically;
with control.k_estimation on, also k_estimate.png from joints.csv's k_est_ columns)
"""
import math
import sys

from flexgait_plotting import cell, column, has_column, read_table, read_table_if_present, save_atomic
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.patches import Polygon  # noqa: E402


def sole_outline(x, y, yaw, length=0.22, width=0.15):
    c, s = math.cos(yaw), math.sin(yaw)
    corners = [(-0.5, -0.5), (0.5, -0.5), (0.5, 0.5), (-0.5, 0.5)]
    return [(x + c * a * length - s * b * width, y + s * a * length + c * b * width) for a, b in corners]


def push_intervals(rows, t):
    """[(start, end)] of each run of logged samples carrying a push force (one per push apart)."""
    if not len(rows) or not has_column(rows, "push_force_x"):
        return []
    out = []
    was_on = False
    for ti, r in zip(t, rows):
        on = any(cell(rows, r, f"push_force_{a}", float) != 0.0 for a in "xyz")
        if on and not was_on:
            out.append([ti, ti])
        elif on:
            out[-1][1] = ti
        was_on = on
    return out


def main(run_dir):
    rows = read_table(run_dir, "log.csv", "humanoid walk")
    steps = read_table(run_dir, "footsteps.csv", "humanoid walk")
    t = column(rows, "t")
    fig, axes = plt.subplots(2, 2, figsize=(13, 8), constrained_layout=True)
    for i, push in enumerate(push_intervals(rows, t)):
        for ax in (axes[0][0], axes[0][1], axes[1][0]):
            ax.axvspan(push[0], max(push[1], push[0] + 0.01), color="tab:orange", alpha=0.25,
                       label="push" if i == 0 else None)
    for ax, axis in ((axes[0][0], "x"), (axes[0][1], "y")):
        ax.plot(t, column(rows, f"zmp_ref_{axis}"), "k--", lw=1.2, label="ZMP reference")
        ax.plot(t, column(rows, f"zmp_true_{axis}"), lw=0.9, label="ZMP (contact forces)")
        ax.plot(t, column(rows, f"zmp_ft_{axis}"), lw=0.7, alpha=0.7, label="ZMP (F/T sensors)")
        ax.plot(t, column(rows, f"com_ref_{axis}"), ":", lw=1.2, label="COM planned")
        ax.plot(t, column(rows, f"com_{axis}"), lw=0.9, label="COM (true)")
        ax.set_xlabel("t [s]")
        ax.set_ylabel(f"{axis} [m]")
        ax.set_title(f"ZMP and COM, {axis}")
        ax.legend(fontsize=8)
    ax = axes[1][0]
    ax.plot(t, column(rows, "imu_roll"), label="pelvis roll (IMU)")
    ax.plot(t, column(rows, "imu_pitch"), label="pelvis pitch (IMU)")
    ax.axhline(0, color="k", lw=0.6)
    ax.set_xlabel("t [s]")
    ax.set_ylabel("angle error [rad]")
    ax.set_title("pelvis attitude against the commanded (level)")
    ax.legend(fontsize=8)
    ax = axes[1][1]
    for r in steps:
        planned = sole_outline(cell(steps, r, "x", float), cell(steps, r, "y", float), cell(steps, r, "yaw", float))
        colour = "tab:blue" if cell(steps, r, "side") == "left" else "tab:red"
        ax.add_patch(Polygon(planned, closed=True, fill=False, ls="--", ec=colour, lw=0.8))
        if cell(steps, r, "landed_x") != "":
            landed = sole_outline(cell(steps, r, "landed_x", float), cell(steps, r, "landed_y", float),
                                  cell(steps, r, "landed_yaw", float))
            ax.add_patch(Polygon(landed, closed=True, fill=True, alpha=0.25, fc=colour, ec=colour))
    ax.plot(column(rows, "zmp_true_x"), column(rows, "zmp_true_y"), lw=0.6, color="k", label="ZMP (true)")
    ax.plot(column(rows, "com_x"), column(rows, "com_y"), lw=0.8, color="tab:green", label="COM (true)")
    ax.set_aspect("equal")
    ax.autoscale_view()
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.set_title("footprints from above (dashed: planned, filled: landed)")
    ax.legend(fontsize=8)
    save_atomic(fig, run_dir, "walk.png")
    plot_k_estimate(run_dir)


def plot_k_estimate(run_dir):
    """The stiffness estimate over time, one line per leg and joint group."""
    rows = read_table_if_present(run_dir, "joints.csv", "humanoid walk")
    if not rows or not has_column(rows, "k_est_l_knee"):
        return
    fig, ax = plt.subplots(figsize=(8, 4), constrained_layout=True)
    t = column(rows, "t")
    for joint, label in (("l_hip_roll", "left roll"), ("l_knee", "left pitch"),
                         ("r_hip_roll", "right roll"), ("r_knee", "right pitch")):
        ax.plot(t, column(rows, f"k_est_{joint}"), lw=0.9, label=label)
    ax.set_xlabel("t [s]")
    ax.set_ylabel("k estimate [Nm/rad]")
    final = [cell(rows, rows.rows[-1], f"k_est_{j}", float) for j in ("l_hip_roll", "l_knee", "r_hip_roll", "r_knee")]
    ax.set_ylim(0, 2.5 * max(final))  # (the first samples, barely excited, swing to the bounds)
    ax.set_title("gear stiffness identified while walking (control.k_estimation)")
    ax.legend(fontsize=8)
    save_atomic(fig, run_dir, "k_estimate.png")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.stderr.write(__doc__)
        sys.exit(2)
    main(sys.argv[1])

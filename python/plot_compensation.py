#!/usr/bin/python3
"""Figures of a compensation study (flexgait humanoid compensation): the thesis's Figs. 13-15.

Usage: plot_compensation.py STUDY_DIR
Reads STUDY_DIR/{off,both,both-thesis-form}/{log,joints}.csv and writes, atomically:
  fig13_pelvis_error.png  pelvis roll and pitch (IMU) against time, off / both / thesis form
  fig14_zmp.png           true ZMP (contact forces) against the reference, y and x, off / both
  estimate.png            stance-leg joint angles: true link, encoder, conventional, Newton
  fig15_output_estimate.png  Newton against conventional estimate over the gravity torque
"""
import os
import sys

from flexgait_plotting import column, has_column, read_table_if_present, save_atomic
import matplotlib.pyplot as plt  # noqa: E402

CASES = (("off", "without compensator", "tab:red"), ("both", "with compensators (full form)", "tab:blue"),
         ("both-thesis-form", "with compensators (thesis form)", "tab:green"))
LEG_JOINTS = ("hip_yaw", "hip_roll", "hip_pitch", "knee", "ankle_pitch", "ankle_roll")


def main(study):
    # Each case is a `humanoid walk` run in its own directory.
    logs = {c: read_table_if_present(os.path.join(study, c), "log.csv", "humanoid walk") for c, _, _ in CASES}

    fig, axes = plt.subplots(2, 1, figsize=(12, 7), sharex=True, constrained_layout=True)
    for ax, angle in zip(axes, ("roll", "pitch")):
        for case, label, colour in CASES:
            if logs[case]:
                ax.plot(column(logs[case], "t"), column(logs[case], f"imu_{angle}"), lw=0.9, color=colour, label=label)
        ax.axhline(0, color="k", lw=0.5)
        ax.set_ylabel(f"pelvis {angle} error [rad]")
        ax.legend(fontsize=8)
    axes[0].set_title("Pelvis angle error (thesis Fig. 13): IMU attitude against level")
    axes[1].set_xlabel("t [s]")
    save_atomic(fig, study, "fig13_pelvis_error.png")

    fig, axes = plt.subplots(2, 1, figsize=(12, 7), sharex=True, constrained_layout=True)
    for ax, axis in zip(axes, ("y", "x")):
        ref = logs["both"] or logs["off"]
        ax.plot(column(ref, "t"), column(ref, f"zmp_ref_{axis}"), "k--", lw=1.2, label="desired ZMP")
        for case, label, colour in CASES[:2]:
            if logs[case]:
                ax.plot(column(logs[case], "t"), column(logs[case], f"zmp_true_{axis}"), lw=0.8, color=colour,
                        label=f"measured ZMP, {label}")
        ax.set_ylabel(f"ZMP {axis} [m]")
        ax.legend(fontsize=8)
    axes[0].set_title("Measured against desired ZMP (thesis Fig. 14)")
    axes[1].set_xlabel("t [s]")
    save_atomic(fig, study, "fig14_zmp.png")

    joints = read_table_if_present(os.path.join(study, "both"), "joints.csv", "humanoid walk")
    if joints:
        t = column(joints, "t")
        fig, axes = plt.subplots(2, 2, figsize=(13, 7), sharex=True, constrained_layout=True)
        for ax, joint in zip(axes.flat, ("l_hip_roll", "l_knee", "l_ankle_pitch", "r_hip_roll")):
            link = column(joints, f"{joint}_link")
            ax.plot(t, [e - l for e, l in zip(column(joints, f"{joint}_encoder"), link)], lw=0.8,
                    label="encoder − true (deflection)")
            ax.plot(t, [e - l for e, l in zip(column(joints, f"{joint}_conventional"), link)], lw=0.8,
                    label="conventional − true")
            ax.plot(t, [e - l for e, l in zip(column(joints, f"{joint}_estimate"), link)], lw=0.8,
                    label="Newton (output compensator) − true")
            ax.axhline(0, color="k", lw=0.5)
            ax.set_title(joint)
            ax.set_ylabel("[rad]")
            ax.legend(fontsize=7)
        for ax in axes[1]:
            ax.set_xlabel("t [s]")
        fig.suptitle("Estimated joint angles against the twin's true link angles (compensators on)")
        save_atomic(fig, study, "estimate.png")

        fig, axes = plt.subplots(1, 3, figsize=(19, 5), constrained_layout=True)
        per_joint = bool(joints) and has_column(joints, "l_hip_roll_per_joint")  # (older files lack the per-joint form)
        for side, prefix in enumerate(("l_", "r_")):
            for joint in ("hip_roll", "hip_pitch", "knee", "ankle_pitch"):
                name = prefix + joint
                tau = column(joints, f"{name}_torque_estimate")
                conventional = column(joints, f"{name}_conventional")
                diff = [n - c for n, c in zip(column(joints, f"{name}_estimate"), conventional)]
                axes[0].scatter(tau, diff, s=2, label=name)
                if per_joint:
                    diff = [p - c for p, c in zip(column(joints, f"{name}_per_joint"), conventional)]
                    axes[1].scatter(tau, diff, s=2, label=name)
                err_n = [n - l for n, l in zip(column(joints, f"{name}_estimate"), column(joints, f"{name}_link"))]
                err_c = [c - l for c, l in zip(conventional, column(joints, f"{name}_link"))]
                axes[2].scatter(tau, err_c, s=2, color="tab:red", alpha=0.4,
                                label="conventional − true" if side == 0 and joint == "hip_roll" else None)
                axes[2].scatter(tau, err_n, s=2, color="tab:blue", alpha=0.4,
                                label="Newton − true" if side == 0 and joint == "hip_roll" else None)
        axes[0].set_title("Proposed (Newton, 12 joints coupled) − conventional estimate")
        axes[1].set_title("Per joint as the thesis (eq. 12 with ∂τ_j/∂θ_j alone) − conventional (Fig. 15)")
        axes[2].set_title("Error of each estimate against the true link angle")
        for ax in axes:
            ax.set_xlabel("gravity torque τ_g(θ̂) of the output compensator [Nm]")
            ax.set_ylabel("[rad]")
            ax.axhline(0, color="k", lw=0.5)
            ax.legend(fontsize=8, markerscale=4)
        save_atomic(fig, study, "fig15_output_estimate.png")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])

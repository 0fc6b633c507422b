#!/usr/bin/python3
"""Figure of a stiffness-mismatch study (flexgait humanoid mismatch).

Usage: plot_mismatch.py STUDY_DIR   (reads comparison.json; writes mismatch.png atomically)
"""
import sys

from flexgait_plotting import field, items, read_summary, save_atomic
import matplotlib.pyplot as plt  # noqa: E402


def main(study):
    rows = items(read_summary(study, "comparison.json", "humanoid mismatch"), "rows")
    labels = [f"{field(r, 'k_joint_true'):.0f}" for r in rows]
    x = range(len(rows))
    fig, ax = plt.subplots(figsize=(8, 4.5), constrained_layout=True)
    off = [field(r, "pelvis_roll_error_max_off") for r in rows]
    on = [field(r, "pelvis_roll_error_max_on") for r in rows]
    ax.bar([i - 0.2 for i in x], off, 0.4, color="tab:red", label="without compensator")
    ax.bar([i + 0.2 for i in x], on, 0.4, color="tab:blue", label="with compensators")
    for i, r in enumerate(rows):
        for dx, fell in ((-0.2, field(r, "fell_off")), (0.2, field(r, "fell_on"))):
            if fell:
                ax.text(i + dx, 0.01, "fell", ha="center", rotation=90)
    ax.set_xticks(list(x), labels)
    ax.set_xlabel(f"true gear stiffness [Nm/rad] (controller's belief {field(rows[0], 'k_joint_belief'):.0f})")
    ax.set_ylabel("peak pelvis roll error [rad]")
    ax.set_title("Compensation with a wrong stiffness model (balance controller on)")
    ax.legend()
    save_atomic(fig, study, "mismatch.png")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])

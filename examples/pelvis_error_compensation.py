#!/usr/bin/python3
"""Pelvis roll error of the humanoid twin with and without the deformation compensators.

Walks the twin at 3 s per step (thesis experiment 3) twice, compensation 'off' and 'both', and
plots the IMU roll against time (thesis Fig. 13b).

Usage: pelvis_error_compensation.py [OUT_DIR] [STEPS]   (writes OUT_DIR/pelvis_error_compensation.png)
"""
import os
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import flexgait  # noqa: E402


def main(out_dir=".", steps=4):
    config = {"walk.step_time": 3.0, "walk.steps": steps}
    fig, ax = plt.subplots(figsize=(9, 4), constrained_layout=True)
    for mode, colour in (("off", "tab:red"), ("both", "tab:blue")):
        run = flexgait.humanoid.walk(config, compensation=mode)
        m = run["summary"]
        ax.plot(run["log"]["t"], run["log"]["imu_roll"], color=colour,
                label=f"compensation {mode}: peak {m['pelvis_roll_error_max']:.4f} rad")
        print(f"compensation {mode}: peak pelvis roll error {m['pelvis_roll_error_max']:.4f} rad, "
              f"fell: {m['fell']}")
    ax.axhline(0, color="k", lw=0.5)
    ax.set_xlabel("t [s]")
    ax.set_ylabel("pelvis roll (IMU) [rad]")
    ax.set_title(f"Pelvis roll error, 3 s/step, {steps} steps (flexgait.humanoid.walk)")
    ax.legend()
    path = os.path.join(out_dir, "pelvis_error_compensation.png")
    fig.savefig(path, dpi=100)
    print(f"wrote {path}")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else ".", int(sys.argv[2]) if len(sys.argv) > 2 else 4)

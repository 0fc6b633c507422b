#!/usr/bin/python3
"""The rimless wheel's gait against the friction coefficient, from Python.

Sweeps mu (mu_s = mu_k) with flexgait.rimless.sweep on two threads (the GIL is released while the
C++ core runs), and plots the fixed point's speed and largest Floquet multiplier, coloured by gait.

Usage: rimless_gait_vs_friction.py [OUT_DIR] [COUNT]   (writes OUT_DIR/rimless_gait_vs_friction.png)
"""
import os
import sys
from concurrent.futures import ThreadPoolExecutor

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import flexgait  # noqa: E402


def main(out_dir=".", count=24):
    # Two halves of the range side by side on two threads.
    halves = [(0.1, 0.35, count // 2), (0.36, 1.2, count - count // 2)]
    with ThreadPoolExecutor(max_workers=2) as pool:
        parts = list(pool.map(lambda h: flexgait.rimless.sweep("rimless.mu", *h), halves))
    mu = np.concatenate([p["value"] for p in parts])
    speed = np.concatenate([p["speed"] for p in parts])
    multiplier = np.concatenate([p["max_multiplier"] for p in parts])  # NaN where no fixed point
    gait = sum((list(p["gait"]) for p in parts), [])
    converged = np.concatenate([p["converged"] for p in parts])  # bool
    speed[~converged] = np.nan  # no periodic gait there

    fig, axes = plt.subplots(2, 1, figsize=(8, 6), sharex=True, constrained_layout=True)
    for name in sorted(set(gait)):
        sel = np.array([g == name for g in gait])
        axes[0].plot(mu[sel], speed[sel], "o", ms=4, label=name)
        axes[1].plot(mu[sel], multiplier[sel], "o", ms=4)
    axes[0].set_ylabel("speed of the periodic gait [m/s]")
    axes[0].legend(fontsize=8)
    axes[1].axhline(1.0, color="k", lw=0.6)
    axes[1].set_ylabel("largest |Floquet multiplier|")
    axes[1].set_xlabel("friction coefficient μ")
    fig.suptitle("Flexible rimless wheel: gait against friction (flexgait.rimless.sweep)")
    path = os.path.join(out_dir, "rimless_gait_vs_friction.png")
    fig.savefig(path, dpi=100)
    print(f"wrote {path}")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else ".", int(sys.argv[2]) if len(sys.argv) > 2 else 24)

#!/usr/bin/python3
"""Figures of the rimless-wheel analyses (flexgait rimless analysis NAME).

Usage: plot_analysis.py NAME RUN_DIR   (writes RUN_DIR/NAME.png atomically)
"""
import math
import os
import subprocess
import sys

from flexgait_plotting import read_rows, save_atomic
import matplotlib.pyplot as plt  # noqa: E402


def rows(run_dir, name):
    return read_rows(os.path.join(run_dir, name))


def gait_vs_friction(run_dir):
    here = os.path.dirname(os.path.abspath(__file__))
    subprocess.run([sys.executable, os.path.join(here, "plot_sweep.py"), run_dir, "friction coefficient mu"], check=True)
    th = rows(run_dir, "thresholds.csv")
    with open(os.path.join(run_dir, "thresholds.txt.tmp"), "w") as f:
        for r in th:
            f.write(f"{r['gait_below']} | {r['gait_above']} at mu = {float(r['threshold']):.4f}\n")
    os.replace(os.path.join(run_dir, "thresholds.txt.tmp"), os.path.join(run_dir, "thresholds.txt"))
    os.replace(os.path.join(run_dir, "sweep.png"), os.path.join(run_dir, "gait-vs-friction.png"))


def energy(run_dir):
    data = rows(run_dir, "energy.csv")
    fig, axes = plt.subplots(2, 1, figsize=(9, 8), constrained_layout=True)
    for mu in sorted({r["mu"] for r in data}, key=float):
        sel = [r for r in data if r["mu"] == mu]
        label = f"mu = {mu} ({sel[0]['gait']})"
        beta = [float(r["beta"]) for r in sel]
        axes[0].plot(beta, [float(r["E_kinetic"]) for r in sel], ".", ms=2, label=label)
        axes[1].plot(beta, [float(r["E_total_minus_start"]) for r in sel], ".", ms=2, label=label)
    axes[0].set_ylabel("kinetic energy [J]")
    axes[1].set_ylabel("E - E(step start) [J]")
    for ax in axes:
        ax.set_xlabel("stance-leg angle beta [rad]")
        ax.legend()
    axes[0].set_title("Single support on the periodic orbit: sticking against slipping")
    save_atomic(fig, run_dir, "energy.png")


def fixed_points(run_dir):
    data = rows(run_dir, "fixed_points.csv")
    fig, ax = plt.subplots(figsize=(7, 7), constrained_layout=True)
    t = [2 * math.pi * k / 200 for k in range(201)]
    ax.plot([math.cos(a) for a in t], [math.sin(a) for a in t], "k--", lw=0.8, label="unit circle")
    for r in data:
        if r["converged"] != "true":
            continue
        pts = [tuple(map(float, m.split(":"))) for m in r["multipliers"].split(";")]
        ax.plot([p[0] for p in pts], [p[1] for p in pts], "o", label=f"mu = {r['mu']}: {r['gait']}")
    ax.set_aspect("equal")
    ax.set_xlabel("Re")
    ax.set_ylabel("Im")
    ax.legend(loc="lower left")
    ax.set_title("Floquet multipliers of the four behaviours")
    save_atomic(fig, run_dir, "fixed-points.png")


def robustness(run_dir):
    data = rows(run_dir, "robustness.csv")
    fig, ax = plt.subplots(figsize=(9, 6), constrained_layout=True)
    keys = sorted({(r["mu"], r["component"], r["sign"]) for r in data}, key=lambda k: (float(k[0]), k[1], k[2]))
    for i, k in enumerate(keys):
        sel = [r for r in data if (r["mu"], r["component"], r["sign"]) == k]
        for r in sel:
            ax.plot(float(r["epsilon"]), i, "o" if r["returned"] == "true" else "x",
                    color="tab:green" if r["returned"] == "true" else "tab:red")
    ax.set_yticks(range(len(keys)))
    ax.set_yticklabels([f"mu={k[0]} {k[1]} {'+' if k[2] == '1' else '-'}" for k in keys])
    ax.set_xscale("log")
    ax.set_xlabel("perturbation (fraction of the component's scale)")
    ax.set_title("Return to the fixed point (o) or not (x)")
    save_atomic(fig, run_dir, "robustness.png")


def stagnation(run_dir):
    data = rows(run_dir, "stagnation.csv")
    w = [float(r["omega0"]) for r in data]
    fig, axes = plt.subplots(2, 1, figsize=(9, 8), sharex=True, constrained_layout=True)
    axes[0].plot(w, [float(r["slide_time_upright"]) for r in data], "o-", ms=3)
    axes[0].set_ylabel("sliding time near upright [s]")
    axes[1].plot(w, [float(r["final_energy"]) for r in data], "o-", ms=3)
    axes[1].set_ylabel("final kinetic + spring energy [J]")
    axes[1].set_xlabel("initial angular velocity omega0 [rad/s]")
    axes[0].set_title("Stagnation interval (paper Fig. 12)")
    save_atomic(fig, run_dir, "stagnation.png")


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.stderr.write(__doc__)
        sys.exit(2)
    {"gait-vs-friction": gait_vs_friction, "energy": energy, "fixed-points": fixed_points,
     "robustness": robustness, "stagnation": stagnation}[sys.argv[1]](sys.argv[2])

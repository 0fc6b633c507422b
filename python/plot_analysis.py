#!/usr/bin/python3
"""Figures of the rimless-wheel analyses (flexgait rimless analysis NAME).

Usage: plot_analysis.py NAME RUN_DIR [PARAM]   (writes RUN_DIR/NAME.png atomically; orbit-diagram writes
orbit.png, basin basin.png, PARAM labels the orbit diagram's axis)
"""
import math
import os
import subprocess
import sys

from atomic_write import write_text_atomic
from flexgait_plotting import cell, field, read_summary, read_table, save_atomic
import plot_maps
import matplotlib.pyplot as plt  # noqa: E402


def gait_vs_friction(run_dir):
    here = os.path.dirname(os.path.abspath(__file__))
    subprocess.run([sys.executable, os.path.join(here, "plot_sweep.py"), run_dir, "friction coefficient mu"], check=True)
    th = read_table(run_dir, "thresholds.csv", "rimless analysis gait-vs-friction")
    write_text_atomic(run_dir, "thresholds.txt",
                      "".join(f"{cell(th, r, 'gait_below')} | {cell(th, r, 'gait_above')} at mu = "
                              f"{cell(th, r, 'threshold', float):.4f}\n" for r in th))
    os.replace(os.path.join(run_dir, "sweep.png"), os.path.join(run_dir, "gait-vs-friction.png"))


def energy(run_dir):
    data = read_table(run_dir, "energy.csv", "rimless analysis energy")
    fig, axes = plt.subplots(2, 1, figsize=(9, 8), constrained_layout=True)
    for mu in sorted({cell(data, r, "mu") for r in data}, key=float):
        sel = [r for r in data if cell(data, r, "mu") == mu]
        label = f"mu = {mu} ({cell(data, sel[0], 'gait')})"
        beta = [cell(data, r, "beta", float) for r in sel]
        axes[0].plot(beta, [cell(data, r, "E_kinetic", float) for r in sel], ".", ms=2, label=label)
        axes[1].plot(beta, [cell(data, r, "E_total_minus_start", float) for r in sel], ".", ms=2, label=label)
    axes[0].set_ylabel("kinetic energy [J]")
    axes[1].set_ylabel("E - E(step start) [J]")
    for ax in axes:
        ax.set_xlabel("stance-leg angle beta [rad]")
        ax.legend()
    axes[0].set_title("Single support on the periodic orbit: sticking against slipping")
    save_atomic(fig, run_dir, "energy.png")


def fixed_points(run_dir):
    data = read_table(run_dir, "fixed_points.csv", "rimless analysis fixed-points")
    fig, ax = plt.subplots(figsize=(7, 7), constrained_layout=True)
    t = [2 * math.pi * k / 200 for k in range(201)]
    ax.plot([math.cos(a) for a in t], [math.sin(a) for a in t], "k--", lw=0.8, label="unit circle")
    for r in data:
        if cell(data, r, "converged") != "true":
            continue
        pts = [tuple(map(float, m.split(":"))) for m in cell(data, r, "multipliers").split(";")]
        ax.plot([p[0] for p in pts], [p[1] for p in pts], "o",
                label=f"mu = {cell(data, r, 'mu')}: {cell(data, r, 'gait')}")
    ax.set_aspect("equal")
    ax.set_xlabel("Re")
    ax.set_ylabel("Im")
    ax.legend(loc="lower left")
    ax.set_title("Floquet multipliers of the four behaviours")
    save_atomic(fig, run_dir, "fixed-points.png")


def robustness(run_dir):
    data = read_table(run_dir, "robustness.csv", "rimless analysis robustness")
    fig, ax = plt.subplots(figsize=(9, 6), constrained_layout=True)
    key_of = lambda r: (cell(data, r, "mu"), cell(data, r, "component"), cell(data, r, "sign"))  # noqa: E731
    keys = sorted({key_of(r) for r in data}, key=lambda k: (float(k[0]), k[1], k[2]))
    for i, k in enumerate(keys):
        for r in (r for r in data if key_of(r) == k):
            returned = cell(data, r, "returned") == "true"
            ax.plot(cell(data, r, "epsilon", float), i, "o" if returned else "x",
                    color="tab:green" if returned else "tab:red")
    ax.set_yticks(range(len(keys)))
    ax.set_yticklabels([f"mu={k[0]} {k[1]} {'+' if k[2] == '1' else '-'}" for k in keys])
    ax.set_xscale("log")
    ax.set_xlabel("perturbation (fraction of the component's scale)")
    ax.set_title("Return to the fixed point (o) or not (x)")
    save_atomic(fig, run_dir, "robustness.png")


def stagnation(run_dir):
    """Paper Fig. 12: the time the stance foot slides near the true vertical and the mechanical energy
    at the end of the stage against omega0; and the near-vertical time against |omega0 - omega_c|."""
    data = read_table(run_dir, "stagnation.csv", "rimless analysis stagnation")
    summary = read_summary(run_dir, "stagnation.json", "rimless analysis stagnation")
    fig, axes = plt.subplots(3, 1, figsize=(9, 12), constrained_layout=True)
    w = [cell(data, r, "omega0", float) for r in data]
    axes[0].plot(w, [cell(data, r, "slide_near_vertical", float) for r in data], "o-", ms=3,
                 label=f"sliding within {field(summary, 'window')} rad of the vertical")
    axes[0].plot(w, [cell(data, r, "slide_total", float) for r in data], ".-", ms=2, lw=0.8,
                 label="sliding, whole stage")
    axes[0].set_ylabel("sliding time [s]")
    for end, colour in (("next_leg_landed", "tab:green"), ("rolled_back", "tab:red"), ("stagnated", "tab:purple"),
                        ("came_to_rest", "tab:gray"), ("time_limit", "tab:orange"), ("failed", "k")):
        sel = [r for r in data if cell(data, r, "end") == end]
        if sel:
            axes[1].plot([cell(data, r, "omega0", float) for r in sel],
                         [cell(data, r, "energy_end", float) for r in sel], "o", ms=3, color=colour,
                         label=end.replace("_", " "))
    axes[1].set_ylabel("mechanical energy at the end of the stage [J]")
    for ax in axes[:2]:
        ax.set_xlabel("initial angular velocity omega0 [rad/s]")
        ax.legend()
    title = "Stagnation interval (paper Fig. 12)"
    if field(summary, "critical_found"):
        wc = field(summary, "omega_c")
        title += f": omega_c = {wc:.9f} rad/s, {field(summary, 'kind')}"
        for ax in axes[:2]:
            ax.axvline(wc, color="k", lw=0.6, ls=":")
        for side, sign, colour in (("above", 1, "tab:green"), ("below", -1, "tab:red")):
            sel = [r for r in data
                   if cell(data, r, "part") == "scan" and (cell(data, r, "offset", float) > 0) == (sign > 0)]
            d = [abs(cell(data, r, "offset", float)) for r in sel]
            near = [cell(data, r, "slide_near_vertical", float) + cell(data, r, "stick_near_vertical", float)
                    for r in sel]
            axes[2].semilogx(d, near, "o-", ms=3, color=colour,
                             label=f"omega0 {'>' if sign > 0 else '<'} omega_c: "
                                   f"{field(summary, f'growth_{side}'):.3f} s per decade")
        axes[2].axhline(field(summary, "threshold"), color="k", lw=0.6, ls="--",
                        label=f"interval threshold {field(summary, 'threshold'):.3f} s: omega0 in "
                              f"[{field(summary, 'interval_low'):.7f}, {field(summary, 'interval_high'):.7f}]")
        axes[2].invert_xaxis()
        axes[2].set_xlabel("|omega0 - omega_c| [rad/s]")
        axes[2].set_ylabel("time near the vertical [s]")
        axes[2].set_title(f"per decade, pendulum estimates: {field(summary, 'estimate_sliding'):.3f} s "
                          "about the hub "
                          f"(sliding), {field(summary, 'estimate_sticking'):.3f} s about the foot (sticking)")
        axes[2].legend()
    else:
        axes[2].set_axis_off()
    axes[0].set_title(title)
    save_atomic(fig, run_dir, "stagnation.png")


def stagnation_map(run_dir):
    """How the stagnation's growth per decade and the interval's width move with mu - tan(phi), I, C, K."""
    table = read_table(run_dir, "stagnation_map.csv", "rimless analysis stagnation-map")
    data = [r for r in table if cell(table, r, "critical_found") == "true"]
    fig, axes = plt.subplots(2, 1, figsize=(10, 9), constrained_layout=True)
    y = list(range(len(data)))
    labels = [f"{cell(table, r, 'variation')} (mu - tan phi = {cell(table, r, 'mu_minus_tan_slope', float):+.4f})"
              for r in data]
    for key, marker, label in (("growth_slide", "o", "sliding part"), ("growth_stick", "s", "sticking part"),
                               ("estimate_sliding", "|", "estimate: about the hub"),
                               ("estimate_sticking", "x", "estimate: about the foot")):
        axes[0].plot([cell(table, r, key, float) for r in data], y, marker, ms=7, ls="none", label=label)
    axes[0].set_xlabel("time near the vertical per decade of |omega0 - omega_c| [s]")
    axes[0].legend()
    axes[1].semilogx([cell(table, r, "interval_width", float) / cell(table, r, "omega_c", float) for r in data], y,
                     "o", ls="none")
    axes[1].set_xlabel("stagnation interval width / omega_c")
    for ax in axes:
        ax.set_yticks(y)
        ax.set_yticklabels(labels)
        ax.grid(True, lw=0.3)
    axes[0].set_title("Stagnation map: one parameter changed at a time")
    save_atomic(fig, run_dir, "stagnation-map.png")


if __name__ == "__main__":
    if len(sys.argv) == 4 and sys.argv[1] == "orbit-diagram":
        plot_maps.orbit_diagram(sys.argv[2], sys.argv[3])
        sys.exit(0)
    if len(sys.argv) != 3:
        sys.stderr.write(__doc__)
        sys.exit(2)
    {"gait-vs-friction": gait_vs_friction, "energy": energy, "fixed-points": fixed_points,
     "robustness": robustness, "stagnation": stagnation, "stagnation-map": stagnation_map,
     "orbit-diagram": plot_maps.orbit_diagram, "basin": plot_maps.basin}[sys.argv[1]](sys.argv[2])

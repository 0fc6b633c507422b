"""Figures of the rimless maps: the orbit diagram, the basin of attraction and the bifurcation diagram of a
continued branch (flexgait rimless analysis orbit-diagram | basin, flexgait rimless continuation).

Usage: plot_maps.py bifurcation RUN_DIR [PARAM]   (RUN_DIR/branch.csv -> RUN_DIR/branch.png)
The orbit diagram and the basin are drawn through plot_analysis.py."""
import math
import os
import sys

from flexgait_plotting import cell, field, read_summary, read_table, save_atomic
import matplotlib.pyplot as plt  # noqa: E402

COLOURS = ["tab:blue", "tab:orange", "tab:green", "tab:red", "tab:purple", "tab:brown", "tab:pink", "tab:olive",
           "tab:cyan", "tab:gray"]


def _float(text):
    try:
        return float(text)
    except ValueError:
        return math.nan


def draw_branch(ax, rows, column, label_gaits=True, gait_colours=None):
    """Draws `column` of branch.csv rows against the parameter: stable solid, unstable dashed, each run of
    one gait in its colour; special points (the event column) marked."""
    gait_colours = {} if gait_colours is None else gait_colours
    pts = [r for r in rows if not cell(rows, r, "event") or not cell(rows, r, "event").startswith("end")]
    segment = []

    def flush():
        if len(segment) < 2:
            return
        # the run's own rows: not segment[0] (the previous run's end) nor segment[-1] (a located end)
        own = next((r for r in segment[1:] if not cell(rows, r, "event")), segment[-1])
        gait, stable = cell(rows, own, "gait"), cell(rows, own, "stable") == "true"
        colour = gait_colours.setdefault(gait, COLOURS[len(gait_colours) % len(COLOURS)])
        ax.plot([_float(cell(rows, r, "parameter")) for r in segment], [_float(cell(rows, r, column)) for r in segment],
                "-" if stable else "--", color=colour, lw=1.6)

    for r in pts:
        key = (cell(rows, r, "gait"), cell(rows, r, "stable"))
        if segment and (cell(rows, segment[-1], "gait"), cell(rows, segment[-1], "stable")) != key:
            # The segments touch: at the located special point when r is one (the old run ends there),
            # else at the old run's last point.
            if cell(rows, r, "event"):
                segment.append(r)
                flush()
                segment = []
            else:
                last = segment[-1]
                flush()
                segment = [last]
        segment.append(r)
    flush()
    if label_gaits:
        for gait, colour in gait_colours.items():
            ax.plot([], [], "-", color=colour, label=f"gait {gait}")
        ax.plot([], [], "k-", label="stable")
        ax.plot([], [], "k--", label="unstable")
    for r in rows:
        ev = cell(rows, r, "event")
        if ev and ev not in ("start",) and not ev.startswith("end"):
            point = (_float(cell(rows, r, "parameter")), _float(cell(rows, r, column)))
            ax.plot(*point, "kD", ms=6, mfc="none")
            ax.annotate(ev, point, fontsize=7, xytext=(4, 4), textcoords="offset points")


def bifurcation(run_dir, param="parameter"):
    rows = read_table(run_dir, "branch.csv", "rimless continuation")
    fig, axes = plt.subplots(2, 1, figsize=(9, 8), sharex=True, constrained_layout=True)
    colours = {}
    draw_branch(axes[0], rows, "thetad", True, colours)
    draw_branch(axes[1], rows, "abs_lambda_1", False, colours)
    axes[1].axhline(1.0, color="k", lw=0.6, ls=":")
    axes[0].set_ylabel("theta-dot at the section [rad/s]")
    axes[1].set_ylabel("|lambda|max")
    axes[1].set_xlabel(param)
    axes[0].legend(fontsize=8)
    axes[0].set_title("Bifurcation diagram: the continued gait (stable solid, unstable dashed; special points marked)")
    save_atomic(fig, run_dir, "branch.png")


def orbit_diagram(run_dir, param="parameter"):
    orbit = read_table(run_dir, "orbit.csv", "rimless analysis orbit-diagram")
    rows = [r for r in orbit if cell(orbit, r, "step")]
    fig, ax = plt.subplots(figsize=(9, 6), constrained_layout=True)
    gaits = sorted({cell(orbit, r, "gait") for r in rows})
    colours = {}
    for g in gaits:
        sel = [r for r in rows if cell(orbit, r, "gait") == g]
        colours[g] = COLOURS[len(colours) % len(COLOURS)]
        ax.plot([cell(orbit, r, "parameter", float) for r in sel], [cell(orbit, r, "thetad", float) for r in sel], ".",
                ms=2.5, color=colours[g], label=f"steps of gait {g}")
    branches = sorted(f for f in os.listdir(run_dir) if f.startswith("branch_") and f.endswith(".csv"))
    for name in branches:
        branch = read_table(run_dir, name, "rimless analysis orbit-diagram", as_file="branch_K.csv")
        draw_branch(ax, branch, "thetad", False, {g: "k" for g in gaits})
    if branches:
        ax.plot([], [], "k-", label="continued branch, stable")
        ax.plot([], [], "k--", label="continued branch, unstable")
    ax.set_xlabel(param)
    ax.set_ylabel("theta-dot at the section [rad/s]")
    ax.legend(fontsize=8, markerscale=3)
    ax.set_title("Orbit diagram: section values of the recorded steps after the transient")
    save_atomic(fig, run_dir, "orbit.png")


OUTCOME_COLOURS = {"converged": "tab:green", "other_gait": "tab:blue", "step_limit": "tab:olive",
                   "rolled_back": "tab:red", "stopped": "tab:gray", "balanced_at_vertical": "tab:cyan",
                   "slid_away": "tab:orange",
                   "time_limit": "tab:purple", "failed": "k", "infeasible": "#dddddd"}


def basin(run_dir):
    from matplotlib.colors import ListedColormap
    from matplotlib.patches import Patch
    rows = read_table(run_dir, "basin.csv", "rimless analysis basin")
    summary = read_summary(run_dir, "summary.json", "rimless analysis basin")
    x, y = field(summary, "x"), field(summary, "y")
    nx, ny = x["count"], y["count"]
    names = list(OUTCOME_COLOURS)
    grid = [[0] * nx for _ in range(ny)]
    for r in rows:
        i = cell(rows, r, "index", int)
        grid[i // nx][i % nx] = names.index(cell(rows, r, "outcome"))
    fig, ax = plt.subplots(figsize=(8, 6.5), constrained_layout=True)
    dx, dy = (x["to"] - x["from"]) / (nx - 1), (y["to"] - y["from"]) / (ny - 1)
    ax.imshow(grid, origin="lower", aspect="auto", interpolation="nearest",
              cmap=ListedColormap([OUTCOME_COLOURS[n] for n in names]), vmin=-0.5, vmax=len(names) - 0.5,
              extent=(x["from"] - dx / 2, x["to"] + dx / 2, y["from"] - dy / 2, y["to"] + dy / 2))
    present = sorted({cell(rows, r, "outcome") for r in rows}, key=names.index)
    ax.legend(handles=[Patch(facecolor=OUTCOME_COLOURS[n], edgecolor="k", lw=0.3,
                             label=f"{n} ({field(summary, 'outcomes')[n]})") for n in present],
              fontsize=8, loc="upper right")
    ax.set_xlabel(x["key"])
    ax.set_ylabel(y["key"])
    ref = field(summary, "reference")
    gait = ref["gait"] if ref["found"] else "none found"
    ax.set_title(f"Basin of the '{gait}' gait: {field(summary, 'basin_fraction'):.3f} of the grid, "
                 f"area {field(summary, 'basin_area'):.4g} {field(summary, 'area_unit')}")
    save_atomic(fig, run_dir, "basin.png")


if __name__ == "__main__":
    if len(sys.argv) not in (3, 4) or sys.argv[1] != "bifurcation":
        sys.stderr.write(__doc__)
        sys.exit(2)
    bifurcation(*sys.argv[2:])

#!/usr/bin/python3
"""Gait of the flexible rimless wheel against the static friction coefficient, for several
Stribeck velocities.

For each v_s and each mu_s on a grid (mu_k = RATIO * mu_s), runs `flexgait rimless fixed-point`
(start omega0 = 1.5 rad/s, 60 transient steps) and records the fixed point's gait and largest
multiplier; between grid neighbours of different gait the threshold is bisected (10 halvings).
'coulomb' is Coulomb friction with that mu_k (the v_s -> 0 limit), 'coulomb_eq' Coulomb with
mu_k = mu_s (the v_s -> infinity limit). Uses only the command line and the standard library.

Usage: rimless_stribeck_thresholds.py FLEXGAIT_EXE [--vs coulomb,0.01,0.1,1,coulomb_eq]
       [--ratio 0.8] [--from 0.1] [--to 0.45] [--count 71] [--out DIR]
Writes DIR/stribeck_gaits.csv (vs, mu_s, gait, max_multiplier) and DIR/stribeck_thresholds.csv
(vs, from_gait, to_gait, mu_s, half_width); prints the thresholds.
"""
import argparse
import json
import os
import shutil
import subprocess
import tempfile


def fixed_point(exe, vs, ratio, mu_s, run_dir):
    """The fixed point's gait ('none' when Newton finds none) and largest |multiplier|."""
    args = [exe, "rimless", "fixed-point", "--set", f"rimless.mu_s={mu_s!r}", "--set", "initial.omega=1.5",
            "--set", "analysis.transient_steps=60", "--out", run_dir, "--no-plot", "--json"]
    mu_k = mu_s if vs == "coulomb_eq" else ratio * mu_s
    args += ["--set", f"rimless.mu_k={mu_k!r}"]
    if vs not in ("coulomb", "coulomb_eq"):
        args += ["--set", "rimless.friction=stribeck", "--set", f"rimless.stribeck_velocity={vs}"]
    done = subprocess.run(args, capture_output=True, text=True, check=True)
    report = json.loads(done.stdout)
    if not report["converged"]:
        return "none", ""
    return report["gait"], max(abs(complex(*m)) for m in report["multipliers"])


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("exe")
    p.add_argument("--vs", default="coulomb,0.01,0.1,0.3,1,3,coulomb_eq")
    p.add_argument("--ratio", type=float, default=0.8, help="mu_k / mu_s")
    p.add_argument("--from", dest="lo", type=float, default=0.1)
    p.add_argument("--to", dest="hi", type=float, default=0.45)
    p.add_argument("--count", type=int, default=71)
    p.add_argument("--out", default=".")
    a = p.parse_args()
    os.makedirs(a.out, exist_ok=True)
    run_dir = tempfile.mkdtemp(prefix="stribeck_fp_")
    gaits, thresholds = [], []
    for vs in a.vs.split(","):
        grid = [a.lo + (a.hi - a.lo) * i / (a.count - 1) for i in range(a.count)]
        rows = [(mu, *fixed_point(a.exe, vs, a.ratio, mu, run_dir)) for mu in grid]
        gaits += [(vs, *r) for r in rows]
        for (x, gx, _), (y, gy, _) in zip(rows, rows[1:]):
            if gx == gy:
                continue
            for _ in range(10):
                mid = 0.5 * (x + y)
                g = fixed_point(a.exe, vs, a.ratio, mid, run_dir)[0]
                if g == gx:
                    x = mid
                elif g == gy:
                    y = mid
                else:  # a third outcome in between (a narrow window): stop here
                    break
            thresholds.append((vs, gx, gy, 0.5 * (x + y), 0.5 * (y - x)))
            print(f"v_s {vs}: {gx} -> {gy} at mu_s = {0.5 * (x + y):.5f} (+- {0.5 * (y - x):.1e})", flush=True)
    with open(os.path.join(a.out, "stribeck_gaits.csv"), "w") as f:
        f.write("vs,mu_s,gait,max_multiplier\n")
        f.writelines(f"{vs},{mu:.6f},{g},{lam}\n" for vs, mu, g, lam in gaits)
    with open(os.path.join(a.out, "stribeck_thresholds.csv"), "w") as f:
        f.write("vs,from_gait,to_gait,mu_s,half_width\n")
        f.writelines(f"{vs},{gx},{gy},{mu:.6f},{w:.2e}\n" for vs, gx, gy, mu, w in thresholds)
    shutil.rmtree(run_dir, ignore_errors=True)


if __name__ == "__main__":
    main()

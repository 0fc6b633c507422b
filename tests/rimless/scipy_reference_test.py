#!/usr/bin/python3
"""The engine against an independent implementation: bench/rimless_scipy_reference.py (the same
model written again with scipy.integrate.solve_ivp, DOP853, from docs/theory/rimless.md).

Usage: scipy_reference_test.py FLEXGAIT_EXE SOURCE_DIR

configs/rimless.yaml for 3 wheel steps in two regimes: μ = 0.13 (below tan α: the stance foot
slips in single support, slip-stick-slip steps, double-support slips in both directions) and
μ = 5000 (every foot sticks; every landing jams, cos β - μ s sin β < 0, and the impulse stops the
landing and the trailing foot together). Both sides must record the same events (kinds, legs and
the modes after each), the same touchdown times to 1e-8 s and the same states (x, y, θ, ẋ, ẏ, θ̇;
m, rad, m/s, rad/s) before and after each touchdown's reset to 1e-8.

The tolerance: both integrate at rtol 1e-10 and locate events by root finding on their dense
outputs to round-off, so they differ by two integration errors; over 20 steps at μ = 0.6, 0.13
and 5000 the largest differences were 4.8e-10 s and 4.3e-10 (3 steps: below 1e-10). A wrong
force, reset or mode choice moves a touchdown by 1e-4 s or more (one jam impulse that left the
trailing foot out changes ẏ after the landing by 0.5 m/s), far outside 1e-8.
"""
import os
import subprocess
import sys
import tempfile

TOL_T = 1e-8  # s
TOL_Q = 1e-8  # m, rad, m/s, rad/s
STEPS = 3
REGIMES = ("0.13", "5000")


def main(exe, source):
    sys.path.insert(0, os.path.join(source, "bench"))
    import rimless_scipy_reference as reference

    config = os.path.join(source, "configs", "rimless.yaml")
    failures = []
    with tempfile.TemporaryDirectory(prefix="flexgait_scipy_reference_") as tmp:
        for mu in REGIMES:
            sets = [f"rimless.mu_s={mu}", f"rimless.mu_k={mu}"]
            run = os.path.join(tmp, f"mu{mu}")
            cmd = [exe, "rimless", "simulate", "--config", config, "--steps", str(STEPS), "--no-plot", "--out", run]
            for s in sets:
                cmd += ["--set", s]
            subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
            params = reference.parse_params(config, sets)
            params["sim.steps"] = STEPS
            sim = reference.Simulation(params).run()
            r = reference.compare(sim, run)
            print(f"mu = {mu}:")
            for line in r["lines"]:
                print("  " + line)
            if r["mismatch"] or r["events_ref"] != r["events_eng"]:
                failures.append(f"mu = {mu}: the event sequences differ")
            if not r["touchdowns"] == r["touchdowns_eng"] >= STEPS:
                failures.append(f"mu = {mu}: {r['touchdowns']} touchdowns compared of the engine's {r['touchdowns_eng']}")
            if not r["touchdown_dt"] <= TOL_T or not r["dt"] <= TOL_T:
                failures.append(f"mu = {mu}: event times differ by {max(r['dt'], r['touchdown_dt']):.3e} s > {TOL_T}")
            if not r["touchdown_dq"][0] <= TOL_Q or not r["touchdown_dq"][1] <= TOL_Q:
                failures.append(f"mu = {mu}: touchdown states differ by {max(r['touchdown_dq']):.3e} > {TOL_Q}")
    for f in failures:
        print("FAIL: " + f)
    return 1 if failures else 0


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    sys.exit(main(sys.argv[1], sys.argv[2]))

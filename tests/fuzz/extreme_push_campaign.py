#!/usr/bin/env python3
"""A seeded campaign of extreme pushes on a short humanoid walk: no false success.

Each case pushes the walking twin once: a magnitude log-uniform from 10 N to 100 kN, a direction
uniform on the sphere, a duration uniform in 0.01-1 s, at a time uniform over the walk, on the
pelvis or the chest. Every run must end in a named outcome:

  * exit 0, outcome "walked": then the claim is checked against the run's own files by a second
    route, not through the judge that made it: every planned step of footsteps.csv landed within
    half the sole's width (0.075 m) of its plan, the pelvis in log.csv stayed within 0.2 m of the
    walking height (not thrown, not sunk) through the last sample, and both soles' centres end
    within a tenth of the sole's length (2.2 cm) of the floor (flat, not on an edge). A run that
    says walked and fails this is a FALSE SUCCESS.
  * exit 1 with one "error:" line and summary.json's outcome one of the named physical outcomes
    (fell, airborne, slid, flipped, missed step, unsupported, safe stop, simulation failure).
Anything else (a crash, a hang, exit 2, an unnamed outcome) is a defect. Prints the outcome counts
in Markdown and every defect with its replay command; exit 1 if there is any defect.

Usage: extreme_push_campaign.py FLEXGAIT_EXE [--count N] [--seed S] [--steps K] [--timeout T] [--case K]
"""
import argparse
import csv
import json
import math
import os
import random
import subprocess
import sys
import tempfile

import yaml

NAMED = {"pelvis_too_low", "pelvis_tilted", "non_sole_contact", "flipped", "airborne", "slid", "missed_step", "unsupported",
         "safe_stop", "simulation_failure"}
TOLERANCE = 0.075        # half the builtin sole's 0.15 m width [m]
STEP_TIME = 1.0          # [s]


def make_case(rng, steps):
    magnitude = 10.0 ** rng.uniform(1.0, 5.0)
    z = rng.uniform(-1.0, 1.0)
    phi = rng.uniform(0.0, 2.0 * math.pi)
    r = math.sqrt(1.0 - z * z)
    force = [magnitude * r * math.cos(phi), magnitude * r * math.sin(phi), magnitude * z]
    duration = rng.uniform(0.01, 1.0)
    # (the walk: steps from walk.start_time = 1.5 s on, one per second; pushes from 0.2 s to its end)
    t = rng.uniform(0.2, 1.5 + steps * STEP_TIME)
    body = rng.choice(["pelvis", "chest"])
    return ["--set", "walk.steps=%d" % steps, "--set", "walk.step_time=%g" % STEP_TIME,
            "--set", "disturbance.push.time=%.6f" % t, "--set", "disturbance.push.duration=%.6f" % duration,
            "--set", "disturbance.push.body=" + body] + \
           sum([["--set", "disturbance.push.force_%s=%.6f" % (axis, f)] for axis, f in zip("xyz", force)], [])


def pelvis_height(out):
    """walk.pelvis_height as the run used it (config.yaml holds the derived value) [m]."""
    with open(os.path.join(out, "config.yaml")) as f:
        return float(yaml.safe_load(f)["walk"]["pelvis_height"])


def verify_walked(out):
    """The second route: did the run truly walk? Returns '' or what contradicts it."""
    with open(os.path.join(out, "footsteps.csv")) as f:
        steps = [row for row in csv.DictReader(f) if row["kind"] == "step"]
    for row in steps:
        if row["error"] == "":
            return "step %s never landed" % row["step"]
        if float(row["error"]) > TOLERANCE:
            return "step %s landed %.3f m from its plan" % (row["step"], float(row["error"]))
    with open(os.path.join(out, "log.csv")) as f:
        rows = list(csv.DictReader(f))
    if not rows:
        return "an empty log"
    height = pelvis_height(out)
    for row in rows:
        z = float(row["pelvis_z"])
        if abs(z - height) > 0.2:
            return "pelvis at %.3f m at t = %s s" % (z, row["t"])
    last = rows[-1]
    for side in ("l", "r"):
        if abs(float(last[side + "_sole_z"])) > 0.022:
            return "the %s sole ends %.3f m off the floor" % (side, float(last[side + "_sole_z"]))
    return ""


def run_case(exe, args, out, timeout):
    cmd = [exe, "humanoid", "walk", "--out", out, "--json", "--no-plot"] + args
    try:
        p = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return "hang", "no answer in %g s" % timeout
    if p.returncode < 0 or p.returncode >= 128 or "internal error" in p.stderr:
        return "crash", p.stderr.strip()[-300:]
    try:
        summary = json.loads(p.stdout)
    except ValueError:
        return "unclear", "exit %d, stdout is not JSON: %s" % (p.returncode, p.stderr.strip()[-300:])
    outcome = summary.get("outcome")
    if p.returncode == 0:
        if outcome != "walked":
            return "unclear", "exit 0 with outcome %r" % outcome
        why = verify_walked(out)
        return ("false-success", why) if why else ("walked", "")
    if p.returncode == 1:
        if outcome not in NAMED:
            return "unclear", "exit 1 with outcome %r" % outcome
        if not p.stderr.startswith("error: ") or p.stderr.count("\n") != 1:
            return "unclear", "exit 1 without one error line: %r" % p.stderr[-300:]
        return outcome, ""
    return "unclear", "exit %d: %s" % (p.returncode, p.stderr.strip()[-300:])


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("exe")
    ap.add_argument("--count", type=int, default=200)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--steps", type=int, default=3)
    ap.add_argument("--timeout", type=float, default=300)
    ap.add_argument("--case", type=int, default=None, help="run only case K (a replay)")
    a = ap.parse_args()
    counts = {}
    defects = []
    with tempfile.TemporaryDirectory() as work:
        for k in range(a.count):
            if a.case is not None and k != a.case:
                continue
            rng = random.Random("%d:%d" % (a.seed, k))
            args = make_case(rng, a.steps)
            out = os.path.join(work, "run%d" % k)
            outcome, detail = run_case(a.exe, args, out, a.timeout)
            counts[outcome] = counts.get(outcome, 0) + 1
            if a.case is not None:
                print("args:", " ".join(args), "\noutcome:", outcome, detail)
            if outcome in ("false-success", "crash", "hang", "unclear"):
                defects.append("%s case %d: %s\n  args: %s\n  replay: %s %s --seed %d --steps %d --case %d" %
                               (outcome, k, detail, " ".join(args), sys.argv[0], a.exe, a.seed, a.steps, k))
    print("| outcome | runs |")
    print("|---|---|")
    for outcome in sorted(counts):
        print("| %s | %d |" % (outcome, counts[outcome]))
    print("| all | %d |" % sum(counts.values()))
    for d in defects:
        print(d)
    return 1 if defects else 0


if __name__ == "__main__":
    sys.exit(main())

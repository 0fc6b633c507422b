#!/usr/bin/env python3
"""A seeded campaign of bad and extreme inputs, counted per class (issue 17's table).

Each case is one command line (or one Python call) with its expected kind of answer:

  * classes "set-value", "yaml-file", "path", "option": input no command may accept. Expected: a
    clear refusal — exit 2, one line on stderr, --out not created.
  * class "extreme-physics": valid keys at or near the ends of their domains (stiff legs, tiny
    masses, huge gains, extreme friction, fine sampling), on short runs. Expected: exit 0 with
    finite results, exit 1 with a named failure ("error: ..." on stderr), or exit 2 naming the
    keys of an infeasible combination — never a crash, a hang or a silent NaN.
  * class "python": bad calls to the bindings. Expected: ValueError, or TypeError where the
    argument's type is wrong (Python's convention) — never another exception, never a crash.

Every answer is classified: refused (exit 2, one line, nothing written), named-failure (exit 1
with an "error:" line), ok (exit 0, every number in the run's JSON files finite), and the defects
crash (a signal, or "internal error"), hang (no answer within --timeout), silent-nan (exit 0 with
NaN/Inf in summary.json or on stdout), unclear (anything else: exit 2 with several lines or with
files written, exit 0 for bad input, exit 1 without a message). Prints the counts table in
Markdown and the replay command of every defect; exit 1 if there is any defect.

Usage: bad_input_campaign.py FLEXGAIT_EXE [--count N] [--seed S] [--timeout T] [--case K]
                             [--classes a,b] [--pythonpath DIR]
"""
import argparse
import json
import math
import os
import random
import re
import shutil
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import cli_fuzz  # noqa: E402  (its value lists and YAML damage)

CLASSES = ["set-value", "yaml-file", "path", "option", "extreme-physics", "python"]
OUTCOMES = ["refused", "named-failure", "ok", "crash", "hang", "silent-nan", "unclear"]
DEFECTS = {"crash", "hang", "silent-nan", "unclear"}

# The commands that read a configuration, with the schema each reads, and short-run settings so
# that an accepted input finishes in seconds.
RUNS = [
    (["rimless", "simulate"], "rimless", ["--set", "sim.steps=3", "--set", "sim.max_wall_time=20"]),
    (["rimless", "fixed-point"], "rimless", ["--set", "analysis.transient_steps=5", "--set", "sim.max_wall_time=20"]),
    (["humanoid", "walk"], "humanoid-walk", ["--set", "walk.steps=2"]),
    (["humanoid", "bench"], "humanoid-bench", []),
]
BAD_OPTIONS = [
    ["rimless", "simulate", "--steps", "-1"], ["rimless", "simulate", "--steps", ""], ["rimless", "simulate", "--omega0", "nan"],
    ["rimless", "simulate", "--model", "elastic"], ["rimless", "fixed-point", "--section", "sideways"],
    ["rimless", "sweep", "--param", "rimless.mu", "--from", "0.2", "--to", "inf", "--count", "3"],
    ["rimless", "sweep", "--param", "rimless.mu", "--from", "0.2", "--to", "0.3", "--count", "0"],
    ["rimless", "sweep", "--param", "rimless.mu", "--from", "0.2", "--to", "0.3", "--count", "3", "--jobs", ""],
    ["rimless", "sweep", "--param", "sim.model", "--from", "0", "--to", "1", "--count", "3"],
    ["rimless", "analysis", "energy", "--mu", ""], ["rimless", "analysis", "energy", "--mu", "0.6,,0.2"],
    ["rimless", "analysis", "energy", "--mu", "-1"], ["rimless", "analysis", "robustness", "--count", "3"],
    ["rimless", "analysis", "teleport"], ["rimless", "continuation", "--param", "rimless.nope", "--from", "0", "--to", "1"],
    ["rimless", "continuation", "--param", "rimless.slope", "--from", "0.1", "--to", "0.1"],
    ["humanoid", "walk", "--fps", "nan", "--render"], ["humanoid", "walk", "--fps", "0", "--render"],
    ["humanoid", "mismatch", "--scales", "nan"], ["humanoid", "mismatch", "--scales", "0.5,,1"],
    ["humanoid", "mismatch", "--scales", "-1"], ["humanoid", "export", "--format", "sdf"], ["fly"],
    ["rimless", "simulate", "--no-such-option"], ["campaign", "rimless-simulate", "--grid", "rimless.K=1:2"],
    ["campaign", "rimless-simulate", "--grid", "rimless.K=-1,2"], ["campaign", "teleport", "--grid", "rimless.K=1,2"],
    ["campaign", "rimless-simulate", "--grid", "rimless.nope=1,2"], ["campaign", "rimless-simulate", "--grid", "=1,2"],
]


def schema(exe):
    out = subprocess.run([exe, "schema"], check=True, capture_output=True, text=True).stdout
    return json.loads(out)["configurations"]


def interval(allowed):
    """The ends of a domain as `flexgait schema` words it ("... in [0, 0.78]", "... > 0",
    ">= 0", "< 1", "<= 1"): (lo, hi, lo_closed, hi_closed), or None for other domains."""
    text = allowed or ""
    m = re.search(r"in ([\[(])\s*([^,\s]+)\s*,\s*([^\])\s]+)\s*([\])])", text)
    try:
        if m:
            return float(m.group(2)), float(m.group(3)), m.group(1) == "[", m.group(4) == "]"
        m = re.search(r"(>=|>|<=|<) *([-+0-9.eE]+)", text)
        if m:
            v = float(m.group(2))
            op = m.group(1)
            return (v, math.inf, op == ">=", False) if op.startswith(">") else (-math.inf, v, False, op == "<=")
    except ValueError:
        return None
    return None


# Keys that set how long a run is: their far ends are long runs, not extreme physics.
RUN_LENGTH_KEYS = {"sim.steps", "walk.steps", "sim.max_time", "sim.max_wall_time", "sim.max_step_time",
                   "sim.max_step_rate", "analysis.transient_steps", "analysis.max_iterations", "output.log_period"}


def extreme_value(rng, p):
    """A valid value at or near an end of the key's domain."""
    ends = interval(p.get("allowed"))
    if p["type"] not in ("real", "integer") or ends is None:
        return None
    lo, hi, lo_closed, hi_closed = ends
    candidates = []
    for end, closed, inward in ((lo, lo_closed, 1.0), (hi, hi_closed, -1.0)):
        if math.isinf(end):  # a huge value of the end's sign
            candidates += [-inward * 1e300, -inward * 1e12]
            continue
        if closed:
            candidates.append(end)
        step = max(abs(end), 1.0) * rng.choice([1e-12, 1e-6, 1e-3])
        candidates.append(end + inward * step)
    values = [v for v in candidates if lo <= v <= hi and (lo_closed or v != lo) and (hi_closed or v != hi)]
    if not values:
        return None
    v = rng.choice(values)
    return str(int(round(v))) if p["type"] == "integer" and abs(v) < 2 ** 31 else repr(v)


def make_cli_case(rng, cls, config, work):
    command, schema_name, short = rng.choice(RUNS)
    keys = config[schema_name]
    names = [p["key"] for p in keys]
    args = list(command) + short
    if cls == "set-value":
        p = rng.choice(keys)
        bad = cli_fuzz.NEVER_VALID_TEXT if p["type"] == "text" else cli_fuzz.NEVER_VALID
        if p["type"] != "text" and rng.random() < 0.3:
            ends = interval(p.get("allowed"))
            if ends and not math.isinf(ends[1]):
                bad = [repr(ends[1] * 2 + 1)]  # outside the domain
        args += ["--set", "%s=%s" % (p["key"], rng.choice(bad))]
    elif cls == "yaml-file":
        path = os.path.join(work, "bad.yaml")
        text = cli_fuzz.mutate_yaml(rng, names)
        text += rng.choice(["a: &a\n  b: *a\n", "k: 1\nk: 2\n", "---\nx: 1\n", "? [a, b]\n: 1\n", "nope.key: 1\n",
                            "%s: [1, 2]\n" % rng.choice(names), "\x00: 1\n"])
        with open(path, "w", encoding="utf-8", errors="surrogateescape") as f:
            f.write(text)
        args += ["--config", path]
    elif cls == "path":
        kind = rng.choice(["missing", "directory", "fifo", "huge", "devzero", "out-is-file", "out-under-file", "empty"])
        if kind == "missing":
            args += ["--config", os.path.join(work, "no", "such.yaml")]
        elif kind == "directory":
            args += ["--config", work]
        elif kind == "fifo":
            fifo = os.path.join(work, "fifo")
            if not os.path.exists(fifo):
                os.mkfifo(fifo)
            args += ["--config", fifo]
        elif kind == "huge":
            huge = os.path.join(work, "huge.yaml")
            if not os.path.exists(huge):
                with open(huge, "w") as f:
                    f.write("# padding\n" * 200000)
            args += ["--config", huge]
        elif kind == "devzero":
            args += ["--config", "/dev/zero"]
        elif kind == "empty":
            args += ["--config", ""]
        else:
            blocker = os.path.join(work, "a_file")
            with open(blocker, "w") as f:
                f.write("x")
            return args, (blocker if kind == "out-is-file" else os.path.join(blocker, "run"))
    elif cls == "option":
        args = list(rng.choice(BAD_OPTIONS))
    elif cls == "extreme-physics":
        physical = [p for p in keys if p["key"] not in RUN_LENGTH_KEYS and
                    not (command == ["rimless", "simulate"] and p["key"].split(".")[0] in ("analysis", "stagnation"))]
        chosen = rng.sample(physical, min(len(physical), rng.randint(1, 3)))
        for p in chosen:
            v = extreme_value(rng, p)
            if v is not None:
                args += ["--set", "%s=%s" % (p["key"], v)]
    return args, None


def non_finite_in(text):
    return re.search(r"(?<![A-Za-z_\"])(-?nan|-?inf|NaN|-?Infinity)(?![A-Za-z_\"])", text) is not None


def classify(proc_code, stdout, stderr, out, expect_refusal):
    if proc_code < 0 or proc_code >= 128 or "internal error" in stderr:
        return "crash"
    lines = stderr.count("\n")
    if proc_code == 2:
        if lines == 1 and stderr.endswith("\n") and not os.path.exists(out):
            return "refused"
        return "unclear"
    if expect_refusal:
        return "unclear"  # bad input accepted
    if proc_code == 1:
        return "named-failure" if re.search(r"^error: ", stderr, re.M) else "unclear"
    if proc_code == 0:
        texts = [stdout]
        for root, _, files in os.walk(out):
            texts += [open(os.path.join(root, f), errors="replace").read() for f in files if f.endswith(".json")]
        return "silent-nan" if any(non_finite_in(t) for t in texts) else "ok"
    return "unclear"


def run_cli_case(exe, args, out_override, work, timeout, expect_refusal):
    out = out_override or os.path.join(work, "out")
    if out_override is None:
        shutil.rmtree(out, ignore_errors=True)
    try:
        p = subprocess.run([exe] + args + ["--out", out, "--no-plot"], capture_output=True, timeout=timeout, cwd=work,
                           env=dict(os.environ, MPLBACKEND="Agg"))
    except subprocess.TimeoutExpired:
        return "hang", ""
    stderr = p.stderr.decode("utf-8", "replace")
    stdout = p.stdout.decode("utf-8", "replace")
    check_out = out if out_override is None else os.path.join(work, "never")
    outcome = classify(p.returncode, stdout, stderr, check_out, expect_refusal)
    return outcome, "exit %d: %s" % (p.returncode, stderr[-600:].strip())


PYTHON_CALLS = [
    "flexgait.rimless.simulate({'rimless.K': -1})", "flexgait.rimless.simulate({'rimless.nope': 1})",
    "flexgait.rimless.simulate({'rimless.mu_s': float('nan')})", "flexgait.rimless.simulate({'rimless.legs': 'ten'})",
    "flexgait.rimless.simulate({'rimless.legs': 2.5})", "flexgait.rimless.simulate({'sim.steps': 0})",
    "flexgait.rimless.simulate(config_file='/no/such.yaml')", "flexgait.rimless.simulate(config_file='/tmp')",
    "flexgait.rimless.simulate({'rimless.mu_s': 0.2, 'rimless.mu_k': 0.3})", "flexgait.rimless.simulate({1: 2})",
    "flexgait.rimless.simulate({'': 1})", "flexgait.rimless.simulate({'a=b': 1})",
    "flexgait.rimless.simulate({'rimless.K': [1, 2]})", "flexgait.rimless.simulate({'rimless.K': None})",
    "flexgait.rimless.simulate({'rimless.K': 'inf'})", "flexgait.rimless.fixed_point({'rimless.K': -1})",
    "flexgait.rimless.poincare_map(z=[None, 1, 2])", "flexgait.rimless.poincare_map(z=[float('nan')] * 3)",
    "flexgait.rimless.poincare_map(z=[])", "flexgait.rimless.poincare_map(z='abc')",
    "flexgait.rimless.sweep('rimless.nope', 0.1, 1.0, 3)", "flexgait.rimless.sweep('rimless.mu', 0.1, 1.0, 0)",
    "flexgait.rimless.sweep('rimless.mu', float('nan'), 1.0, 3)", "flexgait.rimless.sweep('rimless.K', -1, 1, 3)",
    "flexgait.humanoid.walk({'walk.steps': -1})", "flexgait.humanoid.walk({'walk.nope': 1})",
    "flexgait.humanoid.walk({}, compensation='sideways')", "flexgait.humanoid.walk({'walk.step_time': float('inf')})",
    "flexgait.humanoid.bench({'plant.k_joint': -5})", "flexgait.humanoid.bench({'plant.k_joint': 'stiff'})",
    "flexgait.defaults('nothing')", "flexgait.describe('nothing')",
]


def run_python_case(call, pythonpath, timeout):
    code = ("import flexgait, sys\ntry:\n    %s\nexcept (ValueError, TypeError):\n    sys.exit(42)\nexcept Exception as e:\n"
            "    print(type(e).__name__, e, file=sys.stderr)\n    sys.exit(43)\n" % call)
    try:
        p = subprocess.run(["/usr/bin/python3", "-c", code], capture_output=True, timeout=timeout,
                           env=dict(os.environ, PYTHONPATH=pythonpath))
    except subprocess.TimeoutExpired:
        return "hang", ""
    stderr = p.stderr.decode("utf-8", "replace")
    if p.returncode == 42:
        return "refused", ""
    if p.returncode < 0:
        return "crash", "signal %d" % -p.returncode
    return "unclear", "exit %d (no ValueError or TypeError): %s" % (p.returncode, stderr[-400:].strip())


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("exe")
    parser.add_argument("--count", type=int, default=100, help="cases per command-line class")
    parser.add_argument("--seed", type=int, default=17)
    parser.add_argument("--timeout", type=float, default=120)
    parser.add_argument("--case", default=None, help="CLASS:K replays one case")
    parser.add_argument("--classes", default=",".join(CLASSES))
    parser.add_argument("--pythonpath", default=None, help="where the flexgait module is (default: beside the exe)")
    a = parser.parse_args()
    exe = os.path.abspath(a.exe)
    pythonpath = a.pythonpath or os.path.join(os.path.dirname(os.path.dirname(exe)), "bindings", "python")
    config = schema(exe)
    classes = [c for c in a.classes.split(",") if c]
    for c in classes:
        if c not in CLASSES:
            print("error: --classes: unknown class '%s' (allowed: %s)" % (c, ", ".join(CLASSES)), file=sys.stderr)
            return 2
    counts = {c: dict.fromkeys(OUTCOMES, 0) for c in classes}
    defects = []
    only = a.case.split(":") if a.case else None
    with tempfile.TemporaryDirectory() as work:
        for cls in classes:
            n = len(PYTHON_CALLS) if cls == "python" else a.count
            for k in range(n):
                if only and (only[0] != cls or int(only[1]) != k):
                    continue
                if cls == "python":
                    args = PYTHON_CALLS[k]
                    outcome, detail = run_python_case(args, pythonpath, a.timeout)
                else:
                    rng = random.Random("%d:%s:%d" % (a.seed, cls, k))
                    args, out = make_cli_case(rng, cls, config, work)
                    outcome, detail = run_cli_case(exe, args, out, work, a.timeout, cls != "extreme-physics")
                counts[cls][outcome] += 1
                if only:
                    print("args:", args, "\noutcome:", outcome, detail)
                if outcome in DEFECTS:
                    defects.append("%s %s:%d: %s\n  args: %s\n  replay: %s %s --seed %d --case %s:%d" %
                                   (outcome, cls, k, detail, args, sys.argv[0], a.exe, a.seed, cls, k))
    print("| class | tried | " + " | ".join(OUTCOMES) + " |")
    print("|---|---" + "|---" * len(OUTCOMES) + "|")
    for cls in classes:
        row = counts[cls]
        print("| %s | %d | " % (cls, sum(row.values())) + " | ".join(str(row[o]) for o in OUTCOMES) + " |")
    total = {o: sum(counts[c][o] for c in classes) for o in OUTCOMES}
    print("| all | %d | " % sum(total.values()) + " | ".join(str(total[o]) for o in OUTCOMES) + " |")
    for d in defects:
        print(d)
    return 1 if defects else 0


if __name__ == "__main__":
    sys.exit(main())

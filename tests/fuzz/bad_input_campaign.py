#!/usr/bin/env python3
"""A seeded campaign of bad and extreme inputs, counted per class.

Each case is one command line (or one Python call) with its expected kind of answer:

  * classes "set-value", "yaml-file", "path", "option": input no command may accept. Expected: a
    clear refusal — exit 2, one line on stderr, --out not created.
  * class "extreme-physics": valid keys at or near the ends of their domains (stiff legs, tiny
    masses, huge gains, extreme friction, fine sampling), on short runs. Expected: exit 0 with
    finite results, exit 1 with a named failure ("error: ..." on stderr), or exit 2 naming the
    keys of an infeasible combination — never a crash, a hang or a silent NaN.
  * class "campaign": campaign command lines no campaign may accept — axes that set the same key
    (an alias and its parts, over --grid, --random and --set), seeds outside [0, 2^64 - 1], an
    --out that cannot hold a campaign (a file, a path under a file, /dev/null, a directory
    holding a FIFO), --resume where there is none — refused, the target left as it was; and
    resumes from a partial file with damaged cells (exit 0, the same campaign.csv bytes as a
    clean run: no garbage row trusted).
  * class "output-target": every writing command (humanoid export, schema, rimless simulate and
    fixed-point, campaign) with --out naming a FIFO, a socket, /dev/null, a symbolic link to a
    FIFO, a directory (for a file), or a run directory holding a FIFO: refused, the special file
    left as it was, no temporary file left.
  * class "analysis": `rimless continuation` (a random wheel key, ends at or near its bounds,
    reversed or tiny intervals), `analysis orbit-diagram --branch` with a damaged branch.csv (cut,
    another key, section or wheel, columns dropped, garbage cells) and `analysis basin` over
    random ranges, each on the rigid wheel and short. Expected: exit 0, exit 1 with an "error:"
    line, or exit 2 with one line and nothing written — never a crash or an exit above 2.
  * class "robot-file": the builtin robot exported as MJCF or URDF, damaged (cut anywhere, a
    number replaced by nan, inf, -1, 1e308 or text, a tag dropped, bytes inserted, emptied) and
    loaded by `humanoid export --set robot.description=FILE`. Expected as for "analysis".
  * class "export": the builtin robot or a test robot (tests/humanoid/data: -y knees, pitch-roll-yaw
    hips, a waist below the root, printed quaternions, MuJoCo 3 attributes) exported as MJCF or URDF
    with random plant keys at or near the ends of their domains, then the exported file loaded and
    exported again with the configuration the export wrote beside it. Expected for each of the two: exit 0, exit 1
    with an "error:" line, or exit 2 with one line and nothing written — never a crash.
  * class "sensor-fault": a one-step walk whose sensor (F/T, gyro, accelerometer, AHRS or an
    encoder) fails from its first sample or within the first milliseconds (nan, stuck, dropout,
    latency; for 1 ms to the whole walk). Expected: exit 0 with outcome "walked" and finite
    numbers (a fault the controller bridges), or exit 1 with a named outcome in summary.json (a
    safe stop, a fall) — never a simulation failure (a NaN that reached the twin), a crash or a
    hang.
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

CLASSES = ["set-value", "yaml-file", "path", "option", "extreme-physics", "campaign", "output-target", "analysis",
           "robot-file", "export", "sensor-fault", "python"]
SPECIAL_CLASSES = {"campaign", "output-target", "analysis", "robot-file"}
EXE = None  # the flexgait executable (main sets it)
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
                   "sim.max_step_rate", "analysis.transient_steps", "analysis.max_iterations", "output.log_period",
                   "sim.max_log_bytes"}


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


# A cheap campaign (the rigid wheel, one step: each point takes milliseconds).
CHEAP_CAMPAIGN = ["campaign", "rimless-simulate", "--set", "sim.model=rigid", "--set", "sim.steps=1", "--no-plot"]
ALIASES = {"rimless.mu": ["rimless.mu_s", "rimless.mu_k"]}
BAD_SEEDS = ["-1", "18446744073709551616", "99999999999999999999999", "1.5", "1e3", "", " 1", "0x10", "+-1", "nan"]


def file_kind(path):
    """'fifo', 'socket', 'char', 'dir', 'link-to-fifo', 'file', 'absent': what `path` is now."""
    import stat
    try:
        st = os.lstat(path)
    except FileNotFoundError:
        return "absent"
    if stat.S_ISLNK(st.st_mode):
        return "link-to-" + file_kind(os.path.realpath(path))
    for test, name in ((stat.S_ISFIFO, "fifo"), (stat.S_ISSOCK, "socket"), (stat.S_ISCHR, "char"), (stat.S_ISDIR, "dir"),
                       (stat.S_ISREG, "file")):
        if test(st.st_mode):
            return name
    return "other"


def special_target(rng, work, kinds):
    """A fresh special file of one of `kinds` under `work`: (path, kind, what it must stay)."""
    import socket
    kind = rng.choice(kinds)
    base = os.path.join(work, "target-%d" % rng.randrange(10 ** 9))
    if kind == "fifo":
        os.mkfifo(base)
    elif kind == "socket":
        sock = socket.socket(socket.AF_UNIX)
        sock.bind(base)
        sock.close()
    elif kind == "link-to-fifo":
        os.mkfifo(base + ".fifo")
        os.symlink(base + ".fifo", base)
    elif kind == "dir":
        os.mkdir(base)
    elif kind == "file":
        with open(base, "w") as f:
            f.write("mine\n")
    elif kind == "dir-holding-fifo":
        os.mkdir(base)
        os.mkfifo(os.path.join(base, rng.choice(["log.csv", "summary.json", "config.yaml", "campaign.csv"])))
    elif kind == "under-file":
        with open(base, "w") as f:
            f.write("mine\n")
        return os.path.join(base, "run"), kind, None
    elif kind == "dev-null":
        return "/dev/null", kind, "char"
    return base, kind, (kind if kind != "dir-holding-fifo" else None)


def target_intact(path, kind, stays):
    """'' if the target is as it was (and no temporary file is left beside it), else what changed."""
    if kind == "dir-holding-fifo":
        entries = os.listdir(path)
        if len(entries) != 1 or file_kind(os.path.join(path, entries[0])) != "fifo":
            return "the directory now holds %s" % entries
    elif kind == "under-file":
        if file_kind(os.path.dirname(path)) != "file":
            return "the file in the way was replaced"
    elif file_kind(path) != stays:
        return "%s is now %s, was %s" % (path, file_kind(path), stays)
    if kind == "file" and open(path).read() != "mine\n":
        return "the file was changed"
    folder = os.path.dirname(os.path.dirname(path) if kind == "under-file" else path)
    left = [f for f in os.listdir(folder) if ".tmp-" in f]
    return "temporary files left: %s" % left if left else ""


RIGID_SHORT = ["--set", "sim.model=rigid", "--no-plot"]
WHEEL_KEYS = ["rimless.slope", "rimless.I", "rimless.m", "rimless.L0", "rimless.legs", "rimless.mu", "rimless.C",
              "solver.rtol", "initial.omega", "rimless.nothing"]


def base_run(work, name, args):
    """A finished run directory under work (made once): its path."""
    out = os.path.join(work, name)
    if not os.path.exists(os.path.join(out, "complete")):
        subprocess.run([EXE] + args + ["--out", out], capture_output=True, timeout=120)
    return out


def damaged_text(rng, text, numbers=True):
    """text with one random damage: cut, a number replaced, a line dropped, bytes inserted, emptied."""
    kind = rng.choice(["cut", "number", "line", "bytes", "empty"] if numbers else ["cut", "line", "bytes", "empty"])
    if kind == "cut":
        return text[:rng.randrange(len(text) + 1)]
    if kind == "number":
        spans = [m.span() for m in re.finditer(r"-?\d+(\.\d+)?(e[-+]?\d+)?", text)]
        if spans:
            a, b = rng.choice(spans)
            return text[:a] + rng.choice(["nan", "inf", "-1", "1e308", "x", "", "0", "-0", "1e-320"]) + text[b:]
    if kind == "line":
        lines = text.split("\n")
        del lines[rng.randrange(len(lines))]
        return "\n".join(lines)
    if kind == "bytes":
        at = rng.randrange(len(text) + 1)
        return text[:at] + rng.choice(['"', "<", ">", ",", "\x00", "\xff", "&", "\n", "<a>", "]]>"]) + text[at:]
    return ""


def make_analysis_case(rng, work):
    """(argv, post-check) of one continuation, orbit diagram with a damaged --branch, or basin."""
    out = os.path.join(work, "analysis-%d" % rng.randrange(10 ** 9))
    kind = rng.choice(["continuation", "orbit-branch", "basin"])
    if kind == "continuation":
        key = rng.choice(WHEEL_KEYS)
        lo = rng.choice(["0", "1e-12", "0.05", "-0.1", "0.3", "1e300", "nan"])
        hi = rng.choice(["0", "0.1", "0.06", "0.05000001", "0.7", "-1", "inf"])
        args = ["rimless", "continuation", "--param", key, "--from", lo, "--to", hi,
                "--set", "analysis.continuation.max_points=20"] + RIGID_SHORT
        if rng.random() < 0.3:
            args += ["--step", rng.choice(["1e-9", "0.5", "1e-300", "2"])]
    elif kind == "orbit-branch":
        branch_dir = base_run(work, "analysis-branch", ["rimless", "continuation", "--param", "rimless.slope",
                                                        "--from", "0.05", "--to", "0.1"] + RIGID_SHORT)
        text = open(os.path.join(branch_dir, "branch.csv")).read()
        choice = rng.random()
        if choice < 0.2:
            text = text.replace(",rimless.slope,touchdown,", ",rimless.mu,touchdown,")
        elif choice < 0.3:
            text = text.replace(",touchdown,", ",upright,")
        elif choice < 0.4:
            text = text.replace("rimless.m=1.0", "rimless.m=" + rng.choice(["2.0", "nan", "x", ""]))
        else:
            text = damaged_text(rng, text)
        branch = os.path.join(work, "branch-%d.csv" % rng.randrange(10 ** 9))
        with open(branch, "w") as f:
            f.write(text)
        args = ["rimless", "analysis", "orbit-diagram", "--param", rng.choice(["rimless.slope", "rimless.slope",
                                                                               "rimless.L0"]),
                "--from", "0.05", "--to", "0.1", "--count", "2", "--transient", "3", "--record", "2",
                "--branch", branch] + RIGID_SHORT
    else:
        ranges = [rng.choice(["-1:2:2", "0:0:2", "1e300:1e301:2", "-100:100:2", "0.5:1.5:3", "nan:1:2", "1:2:0",
                              "1:2:100000"]) for _ in range(2)]
        args = ["rimless", "analysis", "basin", "--x", "initial.omega", "--y", rng.choice(["initial.beta", "initial.omega"]),
                "--x-range", ranges[0], "--y-range", rng.choice(["-0.1:0.1:2", ranges[1]]),
                "--steps-limit", rng.choice(["3", "0", "-1", "1000000000"])] + RIGID_SHORT
    return args + ["--out", out], lambda: "", out


ROBOTS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "humanoid", "data")


FIXTURES = ["minus_y_knee", "pitch_roll_yaw_hips", "waist_below_root", "printed_quaternions", "mujoco3_attributes",
            "small_biped", "four_sphere_feet", "octagon_sphere_feet", "massless_foot", "unequal_actuators"]


def make_robot_case(rng, work):
    """(argv, post-check, out) of `humanoid export` loading a damaged robot file: the builtin exported, or one of
    the test robots (each a feature of published files) with its mapping."""
    fmt = rng.choice(["mjcf", "urdf", "fixture"])
    if fmt == "fixture":
        robot = rng.choice(FIXTURES)
        base = os.path.join(ROBOTS, robot + ".xml")
        config = os.path.join(ROBOTS, robot + ".yaml")
    else:
        base = os.path.join(work, "robot-base-%s.%s" % (fmt, "xml" if fmt == "mjcf" else "urdf"))
        config = os.path.splitext(base)[0] + ".yaml"
    if not os.path.exists(base):  # writes robot-base-FMT.yaml beside it, the configuration that loads it back
        subprocess.run([EXE, "humanoid", "export", "--format", fmt, "--out", base], capture_output=True, timeout=120)
    damaged = os.path.join(work, "robot-%d.%s" % (rng.randrange(10 ** 9), "urdf" if fmt == "urdf" else "xml"))
    with open(base, errors="replace") as f:
        text = f.read()
    with open(damaged, "w", errors="replace") as f:
        f.write(damaged_text(rng, text))
    out = os.path.join(work, "robot-out-%d.xml" % rng.randrange(10 ** 9))
    args = ["humanoid", "export", "--config", config, "--set", "robot.description=" + damaged]
    return args + ["--out", out], lambda: "", out


def run_export_case(rng, exe, config, work, timeout):
    """Export a robot with random plant keys, then load the exported file and export it again."""
    robot = rng.choice([None] + FIXTURES)
    base = ["--config", os.path.join(ROBOTS, robot + ".yaml")] if robot else []
    fmt = rng.choice(["mjcf", "urdf"])
    keys = [p for p in config["humanoid-walk"] if p["key"].startswith("plant.") and p["type"] in ("real", "integer")]
    for p in rng.sample(keys, rng.randint(0, 3)):
        v = extreme_value(rng, p)
        if v is not None:
            base += ["--set", "%s=%s" % (p["key"], v)]
    first = os.path.join(work, "export-%d.%s" % (rng.randrange(10 ** 9), "xml" if fmt == "mjcf" else "urdf"))
    args = ["humanoid", "export", "--format", fmt] + base + ["--out", first]
    try:
        p = subprocess.run([exe] + args, capture_output=True, timeout=timeout, cwd=work)
    except subprocess.TimeoutExpired:
        return "hang", "", args
    stderr = p.stderr.decode("utf-8", "replace")
    if p.returncode < 0 or p.returncode > 2 or "internal error" in stderr:
        return "crash", "exit %d: %s" % (p.returncode, stderr[-600:].strip()), args
    if p.returncode != 0:
        return run_any_answer_case(exe, args, first, work, timeout) + (args,)
    # Load it back with the configuration the export wrote beside it.
    second = first + ".again.xml"
    reload = ["humanoid", "export", "--format", "mjcf", "--config", os.path.splitext(first)[0] + ".yaml",
              "--out", second]
    return run_any_answer_case(exe, reload, second, work, timeout) + (reload,)


SENSORS = ["ft_left", "ft_right", "gyro", "accel", "ahrs", "encoder"]
ENCODER_JOINTS = ["waist_yaw", "l_hip_roll", "l_hip_pitch", "l_knee", "l_ankle_pitch", "l_ankle_roll", "r_hip_yaw",
                  "r_knee", "r_ankle_roll"]


def make_sensor_fault_case(rng, work):
    """(argv, out) of a one-step walk with one or two sensors failing at start-up."""
    out = os.path.join(work, "fault-%d" % rng.randrange(10 ** 9))
    args = ["humanoid", "walk", "--set", "walk.steps=1", "--no-plot"]
    for sensor in rng.sample(SENSORS, rng.choice([1, 1, 2])):
        kind = rng.choice(["nan", "nan", "stuck", "dropout", "latency"])
        key = "plant.faults.%s." % sensor
        args += ["--set", key + "kind=" + kind,
                 "--set", key + "start=" + rng.choice(["0", "0", "0.001", "0.002", "0.0015", "0.01"]),
                 "--set", key + "duration=" + rng.choice(["0.001", "0.002", "0.01", "0.3", "1e9"])]
        if kind == "latency":
            args += ["--set", key + "delay=" + rng.choice(["0.001", "0.02", "0.2"])]
        if sensor == "encoder":
            args += ["--set", key + "joint=" + rng.choice(ENCODER_JOINTS)]
    return args + ["--out", out], out


def run_sensor_fault_case(exe, args, out, work, timeout):
    """exit 0: walked, finite; exit 1: a named outcome in summary.json, not a simulation failure."""
    defect, code, stderr, detail = run_checked(exe, args, work, timeout)
    if defect:
        return defect, detail
    try:
        text = open(os.path.join(out, "summary.json")).read()
        summary = json.loads(text)
    except (OSError, ValueError):
        return "unclear", detail + " (no readable summary.json)"
    if summary.get("outcome") == "simulation_failure":
        return "unclear", detail + " (the simulation failed: a bad reading reached the twin)"
    if code == 0:
        if non_finite_in(text):
            return "silent-nan", detail
        return ("ok" if summary.get("outcome") == "walked" else "unclear"), detail
    named = code == 1 and re.search(r"^error: ", stderr, re.M) and summary.get("outcome") not in (None, "walked")
    return ("named-failure" if named else "unclear"), detail


def make_special_case(rng, cls, work):
    """(argv without the exe, post-check returning '' or a problem, expect_ok)."""
    if cls == "output-target":
        command = rng.choice([["humanoid", "export"], ["humanoid", "export", "--format", "urdf"], ["schema"],
                              ["rimless", "simulate", "--set", "sim.steps=1", "--no-plot"],
                              ["rimless", "fixed-point", "--set", "sim.model=rigid", "--no-plot"],
                              CHEAP_CAMPAIGN + ["--grid", "rimless.slope=0.05,0.1"]])
        writes_file = command[0] in ("humanoid", "schema")
        kinds = ["fifo", "socket", "link-to-fifo", "dev-null"] + (["dir"] if writes_file else ["dir-holding-fifo", "file"])
        path, kind, stays = special_target(rng, work, kinds)
        return command + ["--out", path], lambda: target_intact(path, kind, stays), False
    # campaign
    kind = rng.choice(["alias", "set-and-axis", "seed", "out", "resume-nothing", "resume-garbage"])
    out = os.path.join(work, "campaign-%d" % rng.randrange(10 ** 9))
    absent = lambda: "" if not os.path.exists(out) else "%s written" % out  # noqa: E731
    if kind == "alias":
        alias, parts = next(iter(ALIASES.items()))
        keys = [alias, rng.choice(parts)]
        rng.shuffle(keys)
        axes = []
        for key in keys:
            if rng.random() < 0.3:
                axes += ["--random", key + "=0.3:0.5"]
            else:
                axes += ["--grid", key + "=0.3,0.5"]
        if "--random" in axes:
            axes += ["--samples", "2"]
        return CHEAP_CAMPAIGN + axes + ["--out", out], absent, False
    if kind == "set-and-axis":
        alias, parts = next(iter(ALIASES.items()))
        given, axis = rng.choice([(p, alias) for p in parts] + [(alias_part, alias_part) for alias_part in parts])
        value = "0.6" if given != "rimless.mu_k" else "0.2"
        return CHEAP_CAMPAIGN + ["--set", "%s=%s" % (given, value), "--grid", axis + "=0.3,0.5", "--out", out], absent, False
    if kind == "seed":
        return CHEAP_CAMPAIGN + ["--random", "rimless.slope=0.05:0.1", "--samples", "2", "--seed", rng.choice(BAD_SEEDS),
                                 "--out", out], absent, False
    if kind == "out":
        path, target, stays = special_target(rng, work, ["file", "under-file", "dev-null", "fifo", "dir-holding-fifo"])
        return (CHEAP_CAMPAIGN + ["--grid", "rimless.slope=0.05,0.1", "--out", path],
                lambda: target_intact(path, target, stays), False)
    if kind == "resume-nothing":
        return CHEAP_CAMPAIGN + ["--grid", "rimless.slope=0.05,0.1", "--resume", "--out", out], absent, False
    # resume-garbage: a finished campaign's rows with cells damaged, resumed: the same bytes as clean.
    grid = ["--grid", "rimless.slope=0.05:0.1:3", "--grid", "rimless.mu=0.4,0.8", "--jobs", "1"]
    clean = os.path.join(work, "clean-campaign")
    if not os.path.exists(os.path.join(clean, "campaign.csv")):
        subprocess.run([EXE] + CHEAP_CAMPAIGN + grid + ["--out", clean], capture_output=True, timeout=120)
    os.makedirs(out)
    shutil.copy(os.path.join(clean, "campaign.signature"), out)
    import csv
    with open(os.path.join(clean, "campaign.csv"), newline="") as f:
        rows = list(csv.reader(f))[1:]
    # Damage that no row of this campaign can hold: an axis value of another point, or a number
    # or a boolean cell turned into text that is neither (a plausible wrong number cannot be told
    # from a right one, by any reader).
    def is_number_or_boolean(cell):
        try:
            return math.isfinite(float(cell))
        except ValueError:
            return cell in ("true", "false")
    for row in rows:
        if rng.random() < 0.5:
            typed = [c for c in range(3, len(row) - 1) if is_number_or_boolean(row[c])]
            if rng.random() < 0.3 or not typed:
                row[rng.choice([1, 2])] = rng.choice(["0.7", "x", "", "0.05;0.1"])
            else:
                row[rng.choice(typed)] = rng.choice(["nan", "inf", "-inf", "1e999", "x", "-", "1;x", "0x1", "True"])
    with open(os.path.join(out, "campaign.partial.csv"), "w", newline="") as f:
        csv.writer(f, lineterminator="\n").writerows(rows)

    def same_bytes():
        a, b = os.path.join(clean, "campaign.csv"), os.path.join(out, "campaign.csv")
        if not os.path.exists(b) or open(a, "rb").read() != open(b, "rb").read():
            return "the resumed campaign.csv differs from a clean run's"
        return ""
    return CHEAP_CAMPAIGN + grid + ["--resume", "--out", out], same_bytes, True


def run_exe(exe, args, work, timeout):
    """(exit code, stderr text) of `exe args` in `work`, or None when it does not end in time."""
    try:
        p = subprocess.run([exe] + args, capture_output=True, timeout=timeout, cwd=work,
                           env=dict(os.environ, MPLBACKEND="Agg"))
    except subprocess.TimeoutExpired:
        return None
    return p.returncode, p.stderr.decode("utf-8", "replace")


def run_checked(exe, args, work, timeout):
    """(defect or None, exit code, stderr, detail): "hang" without an answer in time, "crash" for a
    signal, an exit above 2 or "internal error"."""
    ran = run_exe(exe, args, work, timeout)
    if ran is None:
        return "hang", None, "", ""
    code, stderr = ran
    detail = "exit %d: %s" % (code, stderr[-600:].strip())
    crashed = code < 0 or code > 2 or "internal error" in stderr
    return ("crash" if crashed else None), code, stderr, detail


def run_any_answer_case(exe, args, out, work, timeout):
    """A case whose input may be good or bad: exit 0, exit 1 with an "error:" line, or exit 2 with
    one line and `out` not written; a signal, an exit above 2 or "internal error" is a crash."""
    defect, code, stderr, detail = run_checked(exe, args, work, timeout)
    if defect:
        return defect, detail
    if code == 2:
        errors = [line for line in stderr.splitlines() if line.startswith("error: ")]
        ok = len(errors) == 1 and stderr.rstrip("\n").endswith(errors[0]) and not os.path.exists(out)
        return ("refused" if ok else "unclear"), detail
    if code == 1:
        return ("named-failure" if re.search(r"^error: ", stderr, re.M) else "unclear"), detail
    return "ok", detail


def run_special_case(exe, args, post_check, expect_ok, work, timeout):
    ran = run_exe(exe, args, work, timeout)
    if ran is None:
        return "hang", ""
    code, stderr = ran
    if code < 0 or code >= 128 or "internal error" in stderr:
        return "crash", "exit %d: %s" % (code, stderr[-600:].strip())
    problem = post_check()
    if expect_ok:
        outcome = "ok" if code == 0 and not problem else "unclear"
    else:
        one_line = stderr.count("\n") == 1 and stderr.endswith("\n")
        outcome = "refused" if code == 2 and one_line and not problem else "unclear"
    return outcome, "exit %d: %s %s" % (code, stderr[-600:].strip(), problem)


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
    "flexgait.rimless.sweep('rimless.mu', 0.1, 1.0, 1000001)", "flexgait.rimless.simulate({'sim.sample_dt': 1e-6})",
    "flexgait.rimless.simulate({'sim.sample_dt': 1e-4, 'sim.max_log_bytes': 1e6})",
    "flexgait.rimless.continuation('rimless.nothing', 0.05, 0.1)",
    "flexgait.rimless.continuation('rimless.slope', 0.1, 0.1)",
    "flexgait.rimless.basin('initial.omega', (1, 2, 1), 'initial.beta', (-0.3, -0.1, 2))",
    "flexgait.rimless.basin('initial.omega', 'one:two:3', 'initial.beta', (-0.3, -0.1, 2))",
    "flexgait.rimless.basin('rimless.K', (1, 2, 2), 'initial.beta', (-0.3, -0.1, 2))",
    "flexgait.rimless.orbit_diagram('rimless.slope', 0.1, 0.1, 3)",
    "flexgait.rimless.orbit_diagram('rimless.slope', 0.1, 0.2, 1)",
    "flexgait.rimless.gait_vs_friction(-1, 0.5, 3)", "flexgait.rimless.gait_vs_friction(0.1, 0.5, 0)",
    "flexgait.rimless.stagnation({'stagnation.window': -1})",
    "flexgait.campaign('nothing', {'rimless.mu': [0.3]})",
    "flexgait.campaign('rimless-simulate', {'rimless.nothing': [1, 2]})",
    "flexgait.campaign('rimless-simulate', {'rimless.mu': [float('nan')]})",
    "flexgait.campaign('rimless-simulate', {})",
    "flexgait.humanoid.compensation({'walk.steps': -1})", "flexgait.humanoid.export('sdf')",
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
    global EXE
    exe = EXE = os.path.abspath(a.exe)
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
                elif cls == "export":
                    rng = random.Random("%d:%s:%d" % (a.seed, cls, k))
                    outcome, detail, args = run_export_case(rng, exe, config, work, a.timeout)
                elif cls == "sensor-fault":
                    rng = random.Random("%d:%s:%d" % (a.seed, cls, k))
                    args, out = make_sensor_fault_case(rng, work)
                    outcome, detail = run_sensor_fault_case(exe, args, out, work, a.timeout)
                elif cls in ("analysis", "robot-file"):
                    rng = random.Random("%d:%s:%d" % (a.seed, cls, k))
                    make = make_analysis_case if cls == "analysis" else make_robot_case
                    args, _, out = make(rng, work)
                    outcome, detail = run_any_answer_case(exe, args, out, work, a.timeout)
                elif cls in SPECIAL_CLASSES:
                    rng = random.Random("%d:%s:%d" % (a.seed, cls, k))
                    args, post_check, expect_ok = make_special_case(rng, cls, work)
                    outcome, detail = run_special_case(exe, args, post_check, expect_ok, work, a.timeout)
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

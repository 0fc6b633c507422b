#!/usr/bin/env python3
"""Seeded fuzzing of the command line's option and --set parsing and of --config files.

Each case is a command (every subcommand that writes a run) with a handful of options drawn from
valid values, extreme values and malformed ones, plus a --config file made by mutating a valid
configuration (anchors, aliases, duplicate keys, extra documents, deep nesting, control bytes), and
a last --set value that no key accepts — so every case must be refused at once:

  * exit code 2 (never a signal, never 1: bad input is bad usage),
  * exactly one line on stderr,
  * nothing created at --out,
  * within a few seconds (the refusal comes before any computation).

Usage: cli_fuzz.py FLEXGAIT_EXE [--seconds S] [--seed N] [--case K]
Runs cases 0, 1, ... of seed N until S seconds have passed; --case K replays one case and prints it.
"""
import argparse
import json
import os
import random
import shutil
import subprocess
import sys
import tempfile
import time

COMMANDS = {
    ("rimless", "simulate"): ["--model", "--steps", "--omega0"],
    ("rimless", "fixed-point"): ["--model", "--section"],
    ("rimless", "sweep"): ["--param", "--from", "--to", "--count", "--jobs", "--resume", "--model", "--section"],
    ("rimless", "analysis", "energy"): ["--mu", "--from", "--count", "--resume", "--section"],
    ("rimless", "analysis", "gait-vs-friction"): ["--mu", "--from", "--to", "--count", "--jobs", "--resume", "--section"],
    ("rimless", "analysis", "stagnation"): ["--from", "--to", "--count", "--jobs", "--resume"],
    ("rimless", "analysis", "stagnation-map"): ["--from", "--to", "--count", "--jobs", "--resume", "--vary"],
    ("rimless", "analysis", "robustness"): ["--mu", "--resume"],
    ("humanoid", "bench"): [],
    ("humanoid", "walk"): ["--render", "--fps"],
    ("humanoid", "mismatch"): ["--scales"],
    ("humanoid", "compensation"): [],
}
SCHEMA_OF = {"rimless": "rimless", "bench": "humanoid-bench"}
ANALYSIS_KEYS = ["analysis.transient_steps", "analysis.rtol", "analysis.atol", "analysis.newton_tol",
                 "analysis.max_iterations"]
FLAGS = {"--resume", "--render"}

# Values no numeric or choice key accepts, and option values no option accepts.
NEVER_VALID = ["nan", "NaN", "inf", "-inf", "", "abc", "1e400", "-1e400", "1,,2", "0x1p3", " 1", "1 ", "\n1",
               "1\n", "1\t", "\x7f", "１", "1e", "--", "=", "1=2", "x" * 100000, "\u00e9\u00e9", "\x1b[31m"]
# Values that are sometimes valid: in range, out of range, extreme.
SOMETIMES = ["0", "1", "-1", "0.5", "3", "1e-300", "1e308", "-1e308", "2147483648", "-0", "+1", "1.0", "true",
             "false", "flexible", "rigid", "touchdown", "upright", "off", "both", "0.6,0.2", "0.9,1.1"]
YAML_SNIPPETS = ["a: &a\n  b: *a\n", "---\n", "...\n", "? [a, b]\n: 1\n", "{x: 1}: 2\n", "~: 1\n", "k: [1, 2]\n",
                 "k:\n", "&x k: *x\n", "*nope\n", "k: !!binary aGk=\n", "%YAML 1.2\n---\n", "k: 'unterminated\n",
                 "\t k: 1\n", "k: \"\\x00\"\n", "<<: {a: 1}\n", "[" * 300 + "]" * 300 + "\n",
                 "".join("  " * i + "k%d:\n" % i for i in range(40)), "k: |\n  multi\n  line\n", "\ufeffk: 1\n",
                 "k: 1\nk: 2\n"]


def schema_keys(exe):
    out = subprocess.run([exe, "schema"], check=True, capture_output=True, text=True).stdout
    configurations = json.loads(out)["configurations"]
    global TEXT_KEYS
    TEXT_KEYS = {p["key"] for params in configurations.values() for p in params if p["type"] == "text"}
    return {name: [p["key"] for p in params] for name, params in configurations.items()}


TEXT_KEYS = set()  # keys of type text (names, paths): "inf" or "abc" are valid there
NEVER_VALID_TEXT = ["", "\x7f", "\x1b[31m", "a\tb"]


def mutate_yaml(rng, keys):
    lines = []
    for key in rng.sample(keys, min(len(keys), rng.randint(0, 6))):
        head, _, tail = key.rpartition(".")
        lines.append("%s:\n  %s: %s\n" % (head, tail, rng.choice(SOMETIMES + NEVER_VALID[:8])) if head
                     else "%s: 1\n" % key)
    for _ in range(rng.randint(0, 3)):
        lines.insert(rng.randint(0, len(lines)), rng.choice(YAML_SNIPPETS))
    text = "".join(lines)
    for _ in range(rng.randint(0, 3)):  # byte-level damage
        if text:
            i = rng.randrange(len(text))
            text = text[:i] + rng.choice(["\x00", "\n", ":", "&a ", "*a", "-", "{", "]", "'", "\"", " "]) + text[i + 1:]
    return text


def make_case(rng, keys, work):
    command = rng.choice(sorted(COMMANDS))
    schema = keys[SCHEMA_OF.get(command[1], "humanoid-walk")]
    if command[0] == "rimless":
        schema = schema + ANALYSIS_KEYS
    args = list(command)
    if command == ("rimless", "sweep"):  # its required options, maybe replaced below
        args += ["--param", "rimless.mu", "--from", "0.2", "--to", "0.3", "--count", "2"]
    options = COMMANDS[command] + ["--set", "--set", "--set", "--config"]
    for option in rng.sample(options, rng.randint(1, min(4, len(options)))):
        if option in FLAGS:
            args.append(option)
            continue
        if option == "--config":
            path = os.path.join(work, "c.yaml")
            with open(path, "w", encoding="utf-8", errors="surrogateescape") as f:
                f.write(mutate_yaml(rng, schema))
            args += ["--config", path]
            continue
        value = rng.choice(NEVER_VALID if rng.random() < 0.5 else SOMETIMES)
        if option == "--set":
            key = rng.choice(schema + ["nope.key", "", "rimless", "a=b"])
            args += ["--set", "%s=%s" % (key, value) if rng.random() < 0.95 else value]
        else:
            args += [option, value]
    # A value no key accepts, last, so the case must be refused whatever the others did.
    last = rng.choice(schema)
    args += ["--set", "%s=%s" % (last, rng.choice(NEVER_VALID_TEXT if last in TEXT_KEYS else NEVER_VALID[:6]))]
    return args


def run_case(exe, args, work):
    out = os.path.join(work, "out")
    shutil.rmtree(out, ignore_errors=True)
    try:
        p = subprocess.run([exe] + args + ["--out", out, "--no-plot"], capture_output=True, timeout=60,
                           cwd=work, env=dict(os.environ, MPLBACKEND="Agg"))
    except subprocess.TimeoutExpired:
        return "no answer within 60 s (a refusal must come before any computation)"
    stderr = p.stderr.decode("utf-8", "replace")
    if p.returncode != 2:
        return "exit code %d (expected 2): %s" % (p.returncode, stderr[-2000:])
    if stderr.count("\n") != 1 or not stderr.endswith("\n"):
        return "stderr is not one line: %r" % stderr[:2000]
    if os.path.exists(out):
        return "--out was created although the input was refused: %s" % stderr
    return None


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("exe")
    parser.add_argument("--seconds", type=float, default=30)
    parser.add_argument("--seed", type=int, default=17)
    parser.add_argument("--case", type=int, default=None)
    a = parser.parse_args()
    exe = os.path.abspath(a.exe)
    keys = schema_keys(exe)
    failures = 0
    t0 = time.monotonic()
    with tempfile.TemporaryDirectory() as work:
        cases = [a.case] if a.case is not None else range(10 ** 9)
        n = 0
        for k in cases:
            if a.case is None and time.monotonic() - t0 > a.seconds:
                break
            rng = random.Random(a.seed * 1000003 + k)
            args = make_case(rng, keys, work)
            if a.case is not None:
                print("args:", [x if len(x) < 200 else x[:200] + "...(%d bytes)" % len(x) for x in args])
            problem = run_case(exe, args, work)
            n += 1
            if problem:
                failures += 1
                print("FAIL seed %d case %d: %s\n  replay: %s %s --seed %d --case %d" %
                      (a.seed, k, problem, sys.argv[0], a.exe, a.seed, k))
    print("%d cases in %.0f s, %d failures" % (n, time.monotonic() - t0, failures))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())

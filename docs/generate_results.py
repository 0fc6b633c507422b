#!/usr/bin/env python3
"""Writes the documentation's results page from a `flexgait reproduce` run directory.

Usage: generate_results.py RUN_ROOT OUT_DIR

RUN_ROOT is the --out of `flexgait reproduce` (results/reproduce after ./scripts/demo). The page,
OUT_DIR/index.md, holds the reproduction report's tables (the rows of data/report/references.yaml,
read by python/report.py from the run's own files: our number, the thesis's or the paper's, the
verdict and its tolerance), the tables the user guide points to (TABLES below: the located events
of the continued rimless branches, the walking envelope and the push-recovery campaign point by
point) and every figure of the runs with its caption; the figures are copied under OUT_DIR.
Nothing on it is typed by hand.

Without a run (RUN_ROOT is missing or holds no reproduce.json) the page says how to make one;
the documentation builds either way. A run the report cannot read (an older version's, or one
stopped early) gives a page that says why, and a note on stderr.
"""
import csv
import html
import json
import os
import shutil
import sys
from pathlib import Path

SOURCE = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(SOURCE / "python"))
import report  # noqa: E402  (python/report.py: the report's own reading of the runs)

TITLE = "# Results\n\n"

HOW = """These are the numbers of both studies as flexgait measures them, next to the thesis's and the
paper's, each with a verdict (reproduced or differs) and the tolerance it was judged by. They are
generated: `scripts/docs` reads the run directory of `flexgait reproduce` that `./scripts/demo`
writes (`results/reproduce`), or the one `FLEXGAIT_RESULTS` names.
"""


# The run tables: each TITLE, a sentence on how to read it, and its rows read from one file of the
# run directories `flexgait reproduce` writes (the files the commands write themselves, as the
# report's rows read them): (run, file, keep(row) or None, [(header, column, format)]). A format is
# a Python format spec for numbers or "text"; an empty or NaN cell shows as "–".
TABLES = [
    ("Located events of the continued gait branches",
     "The rows of `branch.csv` with an `event` (gait and section-mode changes, folds, Neimark–Sacker "
     "points, the branch's end) of the runs `rimless-mu-continuation` and `rimless-slope-branch` (`rimless "
     "continuation` in μ and in the slope; their commands under Figures); `gait` and `stable` are those of the "
     "fixed point at the event.",
     [("rimless-mu-continuation", "branch.csv"), ("rimless-slope-branch", "branch.csv")],
     lambda r: r["event"] != "",
     [("key", "key", "text"), ("value", "parameter", ".10g"), ("event", "event", "text"),
      ("gait", "gait", "text"), ("stable", "stable", "text")]),
    ("Walking envelope, point by point",
     "One walk per row of `campaign.csv` (campaign `humanoid-walk`): step length [m], step time [s], "
     "compensation, whether the twin fell, its steps, the peak pelvis roll error [rad] (of a fall: up to the "
     "fall) and the ZMP rms in y [m] (true against reference).",
     [("humanoid-envelope", "campaign.csv")],
     None,
     [("step length", "walk.step_length", ".3g"), ("step time", "walk.step_time", ".3g"),
      ("compensation", "control.compensation", "text"), ("fell", "fell", "text"),
      ("steps", "steps_completed", "text"), ("peak roll error", "pelvis_roll_error_max", ".3f"),
      ("ZMP rms y", "zmp_rms_y", ".4f")]),
    ("Largest recoverable push, point by point",
     "One bisection per row of `campaign.csv` (campaign `humanoid-push-recovery`): the largest impulse "
     "recovered and the smallest seen to fall [N s], the capture-point bound [N s] and recovered / bound; "
     "a push toward the swinging foot can exceed the bound (the next step catches it).",
     [("humanoid-push-recovery", "campaign.csv")],
     None,
     [("situation", "push_recovery.situation", "text"), ("direction", "push_recovery.direction", "text"),
      ("compensation", "control.compensation", "text"), ("balance", "balance.mode", "text"),
      ("recovered", "recovered", ".1f"), ("fell at", "fell_at", ".1f"), ("bound", "bound", ".1f"),
      ("fraction", "fraction", ".2f"), ("runs", "runs", "text")]),
]


def cell_text(value, spec):
    if value == "" or value.lower() == "nan":
        return "–"
    return value if spec == "text" else format(float(value), spec)


def run_tables(root, exit_codes):
    """The TABLES as page text; a run that exited non-zero gives a line saying so, a missing file or
    column of a run that succeeded is a ReportError."""
    text = ["\n## Tables of the runs\n"]
    for title, how, sources, keep, columns in TABLES:
        text.append(f"\n### {title}\n\n{how}\n")
        rows, failed = [], []
        for run, name in sources:
            if exit_codes.get(run, 0) != 0:
                failed.append(f"`{run}`: no result, the run exited with {exit_codes[run]}")
                continue
            path = Path(root) / run / name
            try:
                with open(path, newline="", encoding="utf-8") as f:
                    for row in csv.DictReader(f):
                        if keep is None or keep(row):
                            rows.append([cell_text(row[column], spec) for _, column, spec in columns])
            except KeyError as e:
                raise report.ReportError(f"{run}/{name}: no column {e}") from None
        for line in failed:
            text.append(f"\n{line}\n")
        if rows:
            head = "".join(f"<th>{html.escape(h)}</th>" for h, _, _ in columns)
            body = "\n".join("<tr>" + "".join(f"<td>{html.escape(c)}</td>" for c in r) + "</tr>" for r in rows)
            text.append(f"\n```{{raw}} html\n<table class=\"docutils\">\n<tr>{head}</tr>\n{body}\n</table>\n```\n")
    return "".join(text)


def missing_page(reason):
    return (TITLE + HOW + f"\n**This build holds no results:** {reason}. Make them, then rebuild the documentation:\n\n"
            "```sh\n./scripts/demo                      # or: flexgait reproduce --out results/reproduce\n"
            "./scripts/docs\n```\n\n"
            "`flexgait reproduce --quick` makes a shorter variant (coarser sweeps, fewer steps) in a few minutes.\n")


def table(section):
    """The section's rows as an HTML table (the cells are the report's own escaped markup)."""
    head = ("<tr><th>Result</th><th>Ours</th><th>{}</th><th>Verdict (tolerance)</th><th>Run</th></tr>"
            .format(html.escape(section["reference_header"])))
    rows = []
    for row in section["rows"]:
        ours = row["ours"] if row["failed_run_exit_code"] is None else (
            f"no result: the run exited with {row['failed_run_exit_code']}")
        rows.append(f'<tr><td>{row["label"]}</td><td>{ours}</td><td>{html.escape(row["reference"])}<br>'
                    f'<small>{html.escape(row["source"])}</small></td><td><b>{html.escape(row["verdict"])}</b><br>'
                    f'<small>{html.escape(row["tolerance"])}</small></td><td><code>{html.escape(row["run"])}</code>'
                    "</td></tr>")
    return "<table class=\"docutils\">\n" + head + "\n" + "\n".join(rows) + "\n</table>"


def results_page(root, out):
    manifest = report.load_manifest(root)
    references = report.load_references(str(SOURCE / "data" / "report" / "references.yaml"))
    env = report.make_environment(str(SOURCE / "data" / "report"))
    exit_codes = {r["dir"]: r["exit_code"] for r in manifest["runs"]}
    sections = report.render_sections(env, references, report.RunFiles(root), exit_codes)
    captions, problems = references.get("figures", {}), []
    counts = {"reproduced": 0, "differs": 0}
    for section in sections:
        for row in section["rows"]:
            if row["verdict"] in counts:
                counts[row["verdict"]] += 1
    text = [TITLE, HOW, "\nThis page: `flexgait reproduce{}`, {} rows reproduced, {} differ.\n".format(
        " --quick" if manifest["quick"] else "", counts["reproduced"], counts["differs"])]
    if manifest["quick"]:
        text.append("\nThe quick variant: 3 steps of the 24 s/step walk, coarser rimless sweeps, an 8-point "
                    "walking envelope; the full run's numbers differ where those matter.\n")
    for section in sections:
        text.append(f"\n## {section['title']}\n\n```{{raw}} html\n{table(section)}\n```\n")
    text.append(run_tables(root, exit_codes))
    text.append("\n## Figures\n")
    for run in manifest["runs"]:
        shown = report.captioned_figures(root, run["dir"], captions, problems)
        if not shown:
            continue
        text.append(f"\n### {run['title']}\n\n`{run['command']} --out {run['dir']}`")
        text.append(" (exit code {})\n".format(run["exit_code"]) if run["exit_code"] else "\n")
        if run.get("caption"):
            text.append(f"\n{run['caption']}\n")
        for figure in shown:
            target = Path(out) / run["dir"] / figure["file"]
            target.parent.mkdir(parents=True, exist_ok=True)
            shutil.copyfile(Path(root) / run["dir"] / figure["file"], target)
            text.append(f"\n```{{figure}} {run['dir']}/{figure['file']}\n:alt: {figure['file']}\n\n"
                        f"{figure['file']}: {figure['caption']}\n```\n")
    if problems:
        raise report.ReportError("\n".join(problems))
    return "".join(text)


def main(argv):
    if len(argv) != 2:
        sys.exit("usage: generate_results.py RUN_ROOT OUT_DIR")
    root, out = argv
    os.makedirs(out, exist_ok=True)
    if not os.path.isfile(os.path.join(root, "reproduce.json")):
        page = missing_page(f"no `reproduce.json` in `{root}`")
    else:
        try:
            page = results_page(root, out)
        except (report.ReportError, OSError, ValueError, KeyError) as e:
            print(f"generate_results: {root}: not readable as a reproduce run of this version:\n{e}", file=sys.stderr)
            page = missing_page(f"the run in `{root}` could not be read (see the build's log)")
    with open(os.path.join(out, "index.md"), "w", encoding="utf-8") as f:
        f.write(page)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))

#!/usr/bin/env python3
"""Writes the documentation's results page from a `flexgait reproduce` run directory.

Usage: generate_results.py RUN_ROOT OUT_DIR

RUN_ROOT is the --out of `flexgait reproduce` (results/reproduce after ./scripts/demo). The page,
OUT_DIR/index.md, holds the reproduction report's tables (the rows of data/report/references.yaml,
read by python/report.py from the run's own files: our number, the thesis's or the paper's, the
verdict and its tolerance) and every figure of the runs with its caption; the figures are copied
under OUT_DIR. Nothing on it is typed by hand.

Without a run (RUN_ROOT is missing or holds no reproduce.json) the page says how to make one;
the documentation builds either way. A run the report cannot read (an older version's, or one
stopped early) gives a page that says why, and a note on stderr.
"""
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

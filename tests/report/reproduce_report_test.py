#!/usr/bin/python3
"""`flexgait reproduce --quick` end to end: the report has a number in every row's Ours column,
its HTML nests properly, every <img> exists and every run has a figure; and the tables come out
the same when every file only a plotting script writes (PNG, TXT) is gone.

Usage: reproduce_report_test.py FLEXGAIT_EXE SOURCE_DIR   (about 2 minutes)
"""
import glob
import json
import os
import subprocess
import sys
import tempfile

import yaml

import page_check


def fail(message):
    print(f"FAIL: {message}", file=sys.stderr)
    sys.exit(1)


def expect_no_problems(what, problems):
    if problems:
        fail(f"{what}:\n  " + "\n  ".join(problems))


def reference_row_ids(source):
    with open(os.path.join(source, "data", "report", "references.yaml"), encoding="utf-8") as f:
        return [row["id"] for row in yaml.safe_load(f)["rows"]]


def check_report(root, source):
    page = os.path.join(root, "index.html")
    expect_no_problems("index.html", page_check.page_problems(page))
    rows = page_check.table_rows(page)
    missing = [i for i in reference_row_ids(source) if i not in rows]
    expect_no_problems("rows of references.yaml missing from the page", missing)
    parsed = page_check.parse_page(page)
    with open(os.path.join(root, "reproduce.json"), encoding="utf-8") as f:
        runs = [r["dir"] for r in json.load(f)["runs"]]
    expect_no_problems("runs without a figure", [r for r in runs if parsed.run_figures.get(r, 0) == 0])
    return rows


def check_tables_without_plot_files(root, source, rows_before):
    """Deletes what only plotting scripts write, renders again: the tables must not change."""
    for path in glob.glob(os.path.join(root, "**", "*.png"), recursive=True) + \
            glob.glob(os.path.join(root, "**", "*.txt"), recursive=True):
        os.remove(path)
    result = subprocess.run(["/usr/bin/python3", os.path.join(source, "python", "report.py"), root],
                            capture_output=True, text=True)
    if result.returncode != 0:
        fail(f"report.py without the plot files exited with {result.returncode}:\n{result.stderr}")
    rows_after = page_check.table_rows(os.path.join(root, "index.html"))
    changed = [i for i in rows_before if rows_before[i] != rows_after.get(i)]
    expect_no_problems("rows that changed without the plot files", changed)


def main(exe, source_dir):
    with tempfile.TemporaryDirectory(prefix="flexgait-reproduce-") as tmp:
        root = os.path.join(tmp, "out")
        result = subprocess.run([exe, "reproduce", "--quick", "--out", root])
        if result.returncode != 0:
            fail(f"flexgait reproduce --quick exited with {result.returncode}")
        rows = check_report(root, source_dir)
        check_tables_without_plot_files(root, source_dir, rows)
        print(f"OK: {len(rows)} rows, each with a number; every image present")


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])

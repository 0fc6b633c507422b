#!/usr/bin/python3
"""The reproduction report of `flexgait reproduce`: RUN_ROOT/index.html.

Usage: report.py RUN_ROOT [--references FILE] [--template FILE]

Reads RUN_ROOT/reproduce.json (written by `flexgait reproduce`: whether it was the quick variant,
and per run its directory, title, command, exit code and a caption of its figures), the report's rows from
data/report/references.yaml (each row: where our number comes from, the thesis's or the paper's
value and its source) and renders data/report/index.html.j2 with Jinja2 (autoescaped) into
RUN_ROOT/index.html, through a temporary file and a rename.

Our numbers are read only from files the flexgait commands write (summary.json, comparison.json,
CSV files; CSV by the csv module). A missing file, key or column, a key or column that
RUN_ROOT/schema.json does not declare for the run's command, or a value of the wrong type,
fails the report: every such error is printed to stderr, naming the run, the file and the key,
and the exit code is 1. Only when the run itself failed (a non-zero exit code in
reproduce.json) is its row shown as "no result" instead.

Every row carries a verdict: `verdict: {reproduced: EXPRESSION, tolerance: TEXT}`, a Jinja2
expression over the row's values that is true when our number matches the reference within the
tolerance the text states; the page shows "reproduced" or "differs" and the tolerance. Every
figure of a run has a caption with its units: `figures:` maps a file name pattern ("RUN/NAME.png"
or "NAME.png", fnmatch patterns; the run's own first) to the caption; a figure without one fails
the report.
"""
import argparse
import csv
import fnmatch
import json
import os
import sys

import jinja2
import markupsafe
import yaml

from atomic_write import write_text_atomic
from flexgait_schema import SchemaError, declared_names, names_asked

DATA_DIR = os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir, "data", "report")
ROW_FIELDS = {"id", "section", "run", "values", "label", "ours", "reference", "source", "verdict"}
VALUE_FIELDS = {"file", "key", "type", "columns"}
VERDICT_FIELDS = {"tolerance", "reproduced"}
# A row's verdict: "reproduced" or "differs" as its expression over the values holds or not.
VERDICTS = {True: "reproduced", False: "differs"}


class ReportError(Exception):
    """A problem with the report's data: the message names the run, the file and the key."""


# ---- typed values ----

KINDS = ("number", "integer", "bool", "text", "optional-number")


def from_json(value, kind):
    """A JSON value checked against its kind (a number must be a JSON number, not text)."""
    if kind == "optional-number" and value is None:
        return None
    expected = {"number": (int, float), "optional-number": (int, float), "integer": int, "bool": bool, "text": str}
    if isinstance(value, bool) != (kind == "bool") or not isinstance(value, expected[kind]):
        raise ValueError(f"{value!r} is not {kind}")
    return value


def from_csv(text, kind):
    """A CSV cell parsed as its kind; an empty cell is none only for optional-number."""
    if kind == "text":
        return text
    if kind == "bool":
        if text not in ("true", "false"):
            raise ValueError(f"{text!r} is not true or false")
        return text == "true"
    if kind == "optional-number" and text == "":
        return None
    try:
        return int(text) if kind == "integer" else float(text)
    except ValueError:
        raise ValueError(f"{text!r} is not {kind}") from None


def convert(value, kind, where, from_text):
    try:
        return from_csv(value, kind) if from_text else from_json(value, kind)
    except ValueError as e:
        raise ReportError(f"{where}: {e}") from None


# ---- the run directories' files ----

class RunFiles:
    """The JSON and CSV files under the run root, each parsed once."""

    def __init__(self, root):
        self.root = root
        self.parsed = {}
        # schema.json (written by `flexgait reproduce` beside the runs): the names each run's
        # command declares; None without it (a hand-made tree).
        self.schema = self._parse("schema.json") if os.path.exists(os.path.join(root, "schema.json")) else None

    def check_declared(self, run, spec, where):
        """ReportError when schema.json declares the run's file but not a name the spec reads."""
        command = (self.schema or {}).get("reproduce", {}).get(run)
        if command is None:
            return
        key = f"{command}: {spec['file']}"
        try:
            names = declared_names(self.schema, key)
        except SchemaError:
            return  # a file the schema does not list yet
        missing = [n for n in names_asked(spec) if n not in names]
        if missing:
            raise ReportError(f"{where}: {', '.join(missing)} not declared for '{key}' in schema.json")

    def load(self, run, name):
        relative = f"{run}/{name}"
        if relative not in self.parsed:
            self.parsed[relative] = self._parse(relative)
        return self.parsed[relative]

    def _parse(self, relative):
        path = os.path.join(self.root, relative)
        try:
            with open(path, newline="", encoding="utf-8") as f:
                if relative.endswith(".csv"):
                    reader = csv.DictReader(f)
                    return {"columns": reader.fieldnames or [], "rows": list(reader)}
                return json.load(f)
        except FileNotFoundError:
            raise ReportError(f"{relative}: file missing") from None
        except (OSError, ValueError, csv.Error) as e:
            raise ReportError(f"{relative}: cannot read: {e}") from None


def json_pointer(document, pointer, where):
    """The value at an RFC 6901 JSON pointer ("/rows/0/k"); ReportError naming it if absent."""
    if pointer == "":
        return document
    if not pointer.startswith("/"):
        raise ReportError(f"{where}: key {pointer!r} is not a JSON pointer (starts with /)")
    node = document
    for token in pointer[1:].split("/"):
        token = token.replace("~1", "/").replace("~0", "~")
        if isinstance(node, dict) and token in node:
            node = node[token]
        elif isinstance(node, list) and token.isdigit() and int(token) < len(node):
            node = node[int(token)]
        else:
            raise ReportError(f"{where}: no key {pointer}")
    return node


def records(items, columns, where, from_text):
    """A list of dicts with exactly `columns`, each converted to its kind."""
    table = []
    for index, item in enumerate(items):
        if not isinstance(item, dict):
            raise ReportError(f"{where}: item {index} is not an object")
        record = {}
        for column, kind in columns.items():
            if column not in item:
                raise ReportError(f"{where}: item {index} has no key {column}")
            record[column] = convert(item[column], kind, f"{where}, row {index + 1}, column {column}", from_text)
        table.append(record)
    return table


def read_value(files, run, spec):
    """One row value as its spec says: a JSON value, or records from a JSON array or a CSV file."""
    name = spec["file"]
    where = f"{run}/{name}"
    files.check_declared(run, spec, where)
    content = files.load(run, name)
    if name.endswith(".csv"):
        missing = [c for c in spec["columns"] if c not in content["columns"]]
        if missing:
            raise ReportError(f"{where}: no column {', '.join(missing)}")
        return records(content["rows"], spec["columns"], where, from_text=True)
    value = json_pointer(content, spec["key"], where)
    if "columns" in spec:
        if not isinstance(value, list):
            raise ReportError(f"{where}: key {spec['key']} is not an array")
        return records(value, spec["columns"], f"{where} {spec['key']}", from_text=False)
    return convert(value, spec.get("type", "number"), f"{where} key {spec['key']}", from_text=False)


# ---- the references file ----

def check_value_spec(row_id, name, spec):
    problems = []
    if not isinstance(spec, dict) or "file" not in spec:
        return [f"row {row_id}: value {name} has no file"]
    unknown = set(spec) - VALUE_FIELDS
    if unknown:
        problems.append(f"row {row_id}: value {name} has unknown fields {sorted(unknown)}")
    is_csv = spec["file"].endswith(".csv")
    if is_csv and "columns" not in spec:
        problems.append(f"row {row_id}: value {name} reads a CSV file and needs columns")
    if not is_csv and "key" not in spec:
        problems.append(f"row {row_id}: value {name} reads a JSON file and needs a key")
    kinds = list(spec.get("columns", {}).values()) + [spec.get("type", "number")]
    problems += [f"row {row_id}: value {name} has unknown type {k}" for k in kinds if k not in KINDS]
    return problems


def check_references(references):
    """Every problem of the references file's structure, as messages."""
    sections = {s["id"] for s in references.get("sections", [])}
    problems, seen = [], set()
    for row in references.get("rows", []):
        row_id = row.get("id", "?")
        if set(row) != ROW_FIELDS:
            problems.append(f"row {row_id}: fields {sorted(set(row))}, expected {sorted(ROW_FIELDS)}")
            continue
        if row_id in seen:
            problems.append(f"row {row_id}: id used twice")
        seen.add(row_id)
        if row["section"] not in sections:
            problems.append(f"row {row_id}: unknown section {row['section']}")
        verdict = row["verdict"]
        if not isinstance(verdict, dict) or set(verdict) != VERDICT_FIELDS or not all(
                isinstance(v, str) and v.strip() for v in verdict.values()):
            problems.append(f"row {row_id}: verdict needs exactly {sorted(VERDICT_FIELDS)}, each a non-empty text")
        for name, spec in row["values"].items():
            if not (isinstance(name, str) and name.isidentifier()):
                problems.append(f"row {row_id}: value name {name!r} is not an identifier (YAML reads on/off/yes/no as booleans)")
            problems += check_value_spec(row_id, name, spec)
    figures = references.get("figures", {})
    if not isinstance(figures, dict) or not all(isinstance(k, str) and isinstance(v, str) and v.strip()
                                                for k, v in figures.items()):
        problems.append("figures: a mapping of file name patterns to non-empty captions")
    return problems


def load_references(path):
    try:
        with open(path, encoding="utf-8") as f:
            references = yaml.safe_load(f)
    except (OSError, yaml.YAMLError) as e:
        raise ReportError(f"{path}: cannot read: {e}") from None
    problems = check_references(references)
    if problems:
        raise ReportError(f"{path}:\n  " + "\n  ".join(problems))
    return references


# ---- rendering ----

def format_number(value, spec):
    """Jinja2 filter fmt: Python's format(value, spec); none (an empty optional cell) is n/a."""
    if isinstance(value, jinja2.Undefined):
        str(value)  # a StrictUndefined raises UndefinedError, naming the undeclared value
    return "n/a" if value is None else format(value, spec)


def where(records, column, value):
    """Jinja2 filter where(COLUMN, VALUE): the records whose COLUMN equals VALUE (a column name may
    hold dots, e.g. a campaign's axis control.compensation, which selectattr would split)."""
    return [r for r in records if r[column] == value]


def make_environment(template_dir):
    env = jinja2.Environment(
        loader=jinja2.FileSystemLoader(template_dir),
        autoescape=True,
        undefined=jinja2.StrictUndefined,
        trim_blocks=True,
        lstrip_blocks=True,
        keep_trailing_newline=True,
    )
    env.filters["fmt"] = format_number
    env.filters["where"] = where
    return env


def render_cell(env, text, values, where):
    """A cell's Jinja2 template rendered (its values escaped) as markup for the page."""
    try:
        return markupsafe.Markup(env.from_string(text).render(values))
    except (jinja2.TemplateError, ValueError, TypeError) as e:
        raise ReportError(f"{where}: {e}") from None


def label_without_values(env, row):
    """The label of a row whose run failed: rendered if it needs no values, else the row's id."""
    try:
        return render_cell(env, row["label"], {}, row["id"])
    except ReportError:
        return row["id"]


def render_row(env, row, files, exit_codes):
    """The row as the page shows it; ReportError if a value is missing from a run that succeeded."""
    run = row["run"]
    shown = {k: row[k] for k in ("id", "run", "reference", "source")}
    try:
        values = {name: read_value(files, run, spec) for name, spec in row["values"].items()}
    except ReportError as e:
        if exit_codes.get(run, 0) == 0:
            raise ReportError(f"row {row['id']}: {e}") from None
        return {**shown, "label": label_without_values(env, row), "ours": "", "failed_run_exit_code": exit_codes[run],
                "verdict": "no result", "tolerance": row["verdict"]["tolerance"]}
    where = f"row {row['id']} ({run})"
    return {**shown, "label": render_cell(env, row["label"], values, where),
            "ours": render_cell(env, row["ours"], values, where), "failed_run_exit_code": None,
            "verdict": judge(env, row, values, where), "tolerance": row["verdict"]["tolerance"]}


def judge(env, row, values, where):
    """The row's verdict: its expression over the values evaluated (it must give true or false)."""
    try:
        result = env.compile_expression(row["verdict"]["reproduced"], undefined_to_none=False)(values)
    except (jinja2.TemplateError, ValueError, TypeError) as e:
        raise ReportError(f"{where}: verdict: {e}") from None
    if not isinstance(result, bool):
        raise ReportError(f"{where}: verdict: {result!r} is not true or false")
    return VERDICTS[result]


def render_sections(env, references, files, exit_codes):
    sections = [{**s, "rows": []} for s in references["sections"]]
    by_id = {s["id"]: s for s in sections}
    problems = []
    for row in references["rows"]:
        try:
            by_id[row["section"]]["rows"].append(render_row(env, row, files, exit_codes))
        except ReportError as e:
            problems.append(str(e))
    if problems:
        raise ReportError("\n".join(problems))
    return sections


def files_ending(root, run_dir, suffix):
    """The files of a run directory (not its subdirectories) whose names end with suffix, sorted."""
    path = os.path.join(root, run_dir)
    if not os.path.isdir(path):
        return []
    return sorted(f for f in os.listdir(path) if f.endswith(suffix) and os.path.isfile(os.path.join(path, f)))


def figures(root, run_dir):
    """The PNG files of a run directory, sorted by name."""
    return files_ending(root, run_dir, ".png")


def videos(root, run_dir):
    """The MP4 files of a run directory (humanoid walk --render), sorted by name."""
    return files_ending(root, run_dir, ".mp4")


def replays(root, run_dir):
    """The interactive replay pages of a run directory (replay.html of humanoid walk and rimless simulate)."""
    return [f for f in files_ending(root, run_dir, ".html") if f == "replay.html"]


def embedded_replays(runs):
    """The runs whose replay the page embeds: the first run with a replay of each study (the run
    directory's first word: rimless, humanoid), in manifest order; the others are linked."""
    seen, embed = set(), set()
    for r in runs:
        study = r["dir"].split("-")[0]
        if r["replays"] and study not in seen:
            seen.add(study)
            embed.add(r["dir"])
    return embed


def caption(captions, run_dir, name):
    """The caption of figure NAME of a run: the first pattern matching RUN/NAME, else NAME."""
    for pattern in (f"{run_dir}/{name}", name):
        for key, text in captions.items():
            if fnmatch.fnmatchcase(pattern, key) and ("/" in key) == ("/" in pattern):
                return text
    return None


def captioned_figures(root, run_dir, captions, problems):
    """The run's figures, each {file, caption}; a figure without a caption is a problem."""
    shown = []
    for name in figures(root, run_dir):
        text = caption(captions, run_dir, name)
        if text is None:
            problems.append(f"{run_dir}/{name}: no caption in the references file's figures")
        shown.append({"file": name, "caption": text or ""})
    return shown


def load_manifest(root):
    path = os.path.join(root, "reproduce.json")
    try:
        with open(path, encoding="utf-8") as f:
            return json.load(f)
    except (OSError, ValueError) as e:
        raise ReportError(f"{path}: cannot read: {e}") from None


def render_page(root, references_path, template_path):
    manifest = load_manifest(root)
    references = load_references(references_path)
    env = make_environment(os.path.dirname(os.path.abspath(template_path)))
    exit_codes = {r["dir"]: r["exit_code"] for r in manifest["runs"]}
    sections = render_sections(env, references, RunFiles(root), exit_codes)
    captions, problems = references.get("figures", {}), []
    runs = [{**r, "caption": r.get("caption", ""), "figures": captioned_figures(root, r["dir"], captions, problems),
             "videos": videos(root, r["dir"]), "replays": replays(root, r["dir"])} for r in manifest["runs"]]
    if problems:
        raise ReportError("\n".join(problems))
    embed = embedded_replays(runs)
    runs = [{**r, "embed_replay": r["dir"] in embed} for r in runs]
    template = env.get_template(os.path.basename(template_path))
    return template.render(quick=manifest["quick"], sections=sections, runs=runs)


def main(argv):
    parser = argparse.ArgumentParser(description="Writes RUN_ROOT/index.html, the reproduction report.")
    parser.add_argument("root", help="the run root of flexgait reproduce (holds reproduce.json)")
    parser.add_argument("--references", default=os.path.join(DATA_DIR, "references.yaml"))
    parser.add_argument("--template", default=os.path.join(DATA_DIR, "index.html.j2"))
    args = parser.parse_args(argv)
    try:
        page = render_page(args.root, args.references, args.template)
    except ReportError as e:
        print(f"report.py: index.html not written:\n{e}", file=sys.stderr)
        return 1
    write_text_atomic(args.root, "index.html", page)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))

"""Shared helpers of the plotting scripts: CSV and JSON reading checked against schema.json, and
atomic PNG writing (matplotlib, Agg).

Every column and field a script reads goes through one accessor -- column(), cell(),
has_column(), field() -- which checks the name against `flexgait schema`'s document
(a renamed field breaks a test, not a figure). The document is the schema.json beside the run (in
RUN_DIR or its parent, as `flexgait reproduce` writes it) or, without one, the output of
`flexgait schema` ($FLEXGAIT_EXE, which the flexgait command sets for its scripts, else
`flexgait` on the PATH). tests/python/plot_schema_test.py reads the same calls statically.
"""
import csv
import json
import os
import shutil
import subprocess

import matplotlib

from atomic_write import temporary_beside
from flexgait_schema import SchemaError

matplotlib.use("Agg")


_schemas = {}


def load_schema(run_dir):
    """schema.json beside RUN_DIR, else the output of `flexgait schema` (cached per source)."""
    for d in (run_dir, os.path.dirname(os.path.abspath(run_dir))):
        path = os.path.join(d, "schema.json")
        if os.path.isfile(path):
            if path not in _schemas:
                with open(path) as f:
                    _schemas[path] = (path, json.load(f))
            return _schemas[path]
    exe = os.environ.get("FLEXGAIT_EXE") or shutil.which("flexgait")
    if not exe:
        raise SchemaError(f"no schema.json in {run_dir} or its parent, and no flexgait to run `flexgait schema` "
                          "(set FLEXGAIT_EXE)")
    if exe not in _schemas:
        text = subprocess.run([exe, "schema"], check=True, capture_output=True, text=True).stdout
        _schemas[exe] = (f"`{exe} schema`", json.loads(text))
    return _schemas[exe]


class TableFile:
    """The rows of one CSV file that `flexgait COMMAND` writes, with its declared columns."""

    def __init__(self, path, key, declared, source, rows, header):
        self.path, self.key, self.declared, self.source = path, key, declared, source
        self.rows, self.header = rows, header
        self.present = set()  # names already checked (cell() is called once per row)

    def __iter__(self):
        return iter(self.rows)

    def __len__(self):
        return len(self.rows)


def _declaration(run_dir, section, key):
    """(source, the entry of schema section SECTION, "tables" or "results", for KEY)."""
    source, schema = load_schema(run_dir)
    entries = schema.get(section, {})
    if key not in entries:
        raise SchemaError(f"{source} declares no {section} entry '{key}' ({section}: {', '.join(entries)})")
    return source, entries[key]


def read_table(run_dir, name, command, as_file=None):
    """RUN_DIR/NAME, a CSV file written by `flexgait COMMAND` (schema.json's "COMMAND: NAME", or
    "COMMAND: AS_FILE" for a file named by a pattern, e.g. branch_K.csv for branch_1.csv)."""
    key = f"{command}: {as_file or name}"
    source, entry = _declaration(run_dir, "tables", key)
    path = os.path.join(run_dir, name)
    with open(path, newline="") as f:
        reader = csv.DictReader(f)
        rows = list(reader)
        header = list(reader.fieldnames or [])
    return TableFile(path, key, entry["columns"], source, rows, header)


def read_table_if_present(run_dir, name, command):
    """read_table, or None when RUN_DIR/NAME does not exist."""
    return read_table(run_dir, name, command) if os.path.exists(os.path.join(run_dir, name)) else None


def _declared(table, name):
    if name not in table.declared:
        raise SchemaError(f"{table.path}: column '{name}' is not declared for '{table.key}' in {table.source}")


def has_column(table, name):
    """Whether the file has the declared column NAME (a column written only under a setting)."""
    _declared(table, name)
    return name in table.header


def _present(table, name):
    if name in table.present:
        return
    _declared(table, name)
    if name not in table.header:
        raise SchemaError(f"{table.path}: no column '{name}' in the file "
                          f"(declared for '{table.key}' in {table.source})")
    table.present.add(name)


def column(table, name, cast=float):
    """The column NAME of every row, each value through CAST."""
    _present(table, name)
    return [cast(r[name]) for r in table.rows]


def cell(table, row, name, cast=str):
    """The value of column NAME in ROW (one of TABLE's rows), through CAST."""
    _present(table, name)
    return cast(row[name])


def read_summary(run_dir, name, command):
    """RUN_DIR/NAME, a JSON file written by `flexgait COMMAND` (schema.json's results "COMMAND: NAME")."""
    key = f"{command}: {name}"
    source, entry = _declaration(run_dir, "results", key)
    path = os.path.join(run_dir, name)
    with open(path) as f:
        document = json.load(f)
    return SummaryFile(path, key, entry["fields"], source, document)


class SummaryFile:
    """A JSON object (a summary, or one item of a list in it) with its declared fields."""

    def __init__(self, path, key, fields, source, document):
        self.path, self.key, self.fields, self.source, self.document = path, key, fields, source, document
        self.declared = [f["key"] for f in fields]


def field(summary, name):
    """The field NAME of a summary read by read_summary."""
    if name not in summary.declared:
        raise SchemaError(f"{summary.path}: field '{name}' is not declared for '{summary.key}' in {summary.source}")
    if name not in summary.document:
        raise SchemaError(f"{summary.path}: no field '{name}' in the file (declared for '{summary.key}')")
    return summary.document[name]


def items(summary, name):
    """The objects of the list field NAME of a summary, each read with field() against its
    declared item fields."""
    value = field(summary, name)
    spec = next(f for f in summary.fields if f["key"] == name)
    if "item_fields" not in spec or not isinstance(value, list):
        raise SchemaError(f"{summary.path}: field '{name}' is not declared as a list of objects in {summary.source}")
    return [SummaryFile(summary.path, f"{summary.key} {name}[]", spec["item_fields"], summary.source, item)
            for item in value]


def read_rows(path):
    """The rows of a CSV file as dictionaries (files without a schema entry)."""
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def save_atomic(fig, run_dir, name, dpi=100):
    """Writes the figure to RUN_DIR/NAME through a temporary file and a rename."""
    with temporary_beside(run_dir, name) as tmp:
        fig.savefig(tmp, dpi=dpi, format=os.path.splitext(name)[1][1:] or "png")

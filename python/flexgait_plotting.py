"""Shared helpers of the plotting scripts: CSV and JSON reading checked against schema.json, and
atomic PNG writing (matplotlib, Agg).

Every column and field a script reads goes through one accessor -- column(), cell(),
has_column(), field() -- which checks the name against `flexgait schema`'s document (issue 13:
a renamed field breaks a test, not a figure). The document is the schema.json beside the run (in
RUN_DIR or its parent, as `flexgait reproduce` writes it) or, without one, the output of
`flexgait schema` ($FLEXGAIT_EXE, which the flexgait command sets for its scripts, else
`flexgait` on the PATH). tests/python/plot_schema_test.py reads the same calls statically.
"""
import csv
import fnmatch
import json
import os
import shutil
import subprocess

import matplotlib

from atomic_write import temporary_beside

matplotlib.use("Agg")


class SchemaError(Exception):
    """A script asked for a column or field that schema.json does not declare, or a file lacks it."""


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

    def __iter__(self):
        return iter(self.rows)

    def __len__(self):
        return len(self.rows)


def read_table(run_dir, name, command):
    """RUN_DIR/NAME, a CSV file written by `flexgait COMMAND` (schema.json's "COMMAND: NAME")."""
    source, schema = load_schema(run_dir)
    key = f"{command}: {name}"
    tables = schema.get("tables", {})
    if key not in tables:
        raise SchemaError(f"{source} declares no table '{key}' (tables: {', '.join(tables)})")
    path = os.path.join(run_dir, name)
    with open(path, newline="") as f:
        reader = csv.DictReader(f)
        rows = list(reader)
        header = list(reader.fieldnames or [])
    return TableFile(path, key, tables[key]["columns"], source, rows, header)


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
    _declared(table, name)
    if name not in table.header:
        raise SchemaError(f"{table.path}: no column '{name}' in the file (declared for '{table.key}' in {table.source})")


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
    source, schema = load_schema(run_dir)
    key = f"{command}: {name}"
    results = schema.get("results", {})
    if key not in results:
        raise SchemaError(f"{source} declares no result '{key}' (results: {', '.join(results)})")
    path = os.path.join(run_dir, name)
    with open(path) as f:
        document = json.load(f)
    return SummaryFile(path, key, [fl["key"] for fl in results[key]["fields"]], source, document)


class SummaryFile:
    def __init__(self, path, key, declared, source, document):
        self.path, self.key, self.declared, self.source, self.document = path, key, declared, source, document


def field(summary, name):
    """The field NAME of a summary read by read_summary."""
    if name not in summary.declared:
        raise SchemaError(f"{summary.path}: field '{name}' is not declared for '{summary.key}' in {summary.source}")
    if name not in summary.document:
        raise SchemaError(f"{summary.path}: no field '{name}' in the file (declared for '{summary.key}')")
    return summary.document[name]


def declared_names(schema, key):
    """Every column or field name declared for "COMMAND: FILE" (for the static check)."""
    if key in schema.get("tables", {}):
        return list(schema["tables"][key]["columns"])
    if key in schema.get("results", {}):
        return [f["key"] for f in schema["results"][key]["fields"]]
    raise SchemaError(f"schema declares no table or result '{key}'")


def matches(pattern, names):
    """Whether a name (or an f-string's pattern, '*' for each placeholder) names a declared one."""
    return any(fnmatch.fnmatchcase(n, pattern) for n in names)


def read_rows(path):
    """The rows of a CSV file as dictionaries (files without a schema entry)."""
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def save_atomic(fig, run_dir, name, dpi=100):
    """Writes the figure to RUN_DIR/NAME through a temporary file and a rename."""
    with temporary_beside(run_dir, name) as tmp:
        fig.savefig(tmp, dpi=dpi, format=os.path.splitext(name)[1][1:] or "png")

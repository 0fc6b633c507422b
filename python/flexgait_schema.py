"""The names `flexgait schema` declares (schema.json): shared by the plotting scripts
(flexgait_plotting.py), the report (report.py) and tests/python/plot_schema_test.py.

schema.json: "results" {"COMMAND: FILE.json": {"fields": [{key, ..., [item_fields]}]}},
"tables" {"COMMAND: FILE.csv": {"columns": [...]}}, "reproduce" {run directory: COMMAND}.
"""
import re


class SchemaError(Exception):
    """A name that schema.json does not declare, or a file that lacks a declared one."""


def declared_names(schema, key):
    """Every column or field name declared for "COMMAND: FILE" (a result's list items' fields too);
    a numbered file (branch_1.csv) is declared by its pattern (branch_K.csv)."""
    for k in (key, re.sub(r"_[0-9]+[.]csv$", "_K.csv", key)):
        if k in schema.get("tables", {}):
            return list(schema["tables"][k]["columns"])
        if k in schema.get("results", {}):
            fields = schema["results"][k]["fields"]
            return [f["key"] for f in fields] + [i["key"] for f in fields for i in f.get("item_fields", [])]
    raise SchemaError(f"schema declares no table or result '{key}'")


def names_asked(spec):
    """The names a references.yaml value reads: a CSV's columns, or a JSON pointer's first token."""
    if spec["file"].endswith(".csv"):
        return list(spec["columns"])
    return [spec["key"].split("/")[1].replace("~1", "/").replace("~0", "~")] if spec.get("key", "/") != "" else []

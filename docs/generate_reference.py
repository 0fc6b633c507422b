#!/usr/bin/env python3
"""Writes the documentation's generated reference pages from a built flexgait.

Usage: generate_reference.py FLEXGAIT_EXE OUT_DIR

- OUT_DIR/configuration.md: every configuration key of `flexgait schema` (type, default, unit,
  domain, the rule of a derived default, doc), one table per configuration and key group;
- OUT_DIR/results.md: every summary field and every CSV column the commands write;
- OUT_DIR/commands.md: every command's `--help`, found by walking the commands' own
  "Subcommands:" lists.

Nothing here is typed by hand: a key, field or option exists on these pages because the program
declares it. Same program, same pages (byte for byte).
"""
import json
import re
import subprocess
import sys
from pathlib import Path


def run(exe, args):
    done = subprocess.run([exe, *args], capture_output=True, text=True, check=False)
    if done.returncode != 0:
        sys.exit(f"generate_reference: `flexgait {' '.join(args)}` exited {done.returncode}: {done.stderr.strip()}")
    # CLI11's usage lines name the program as it was started: the pages name it `flexgait`.
    return done.stdout.replace(exe, "flexgait")


def cell(value):
    """Text for one Markdown table cell: no raw HTML, no pipes, no math, no line breaks."""
    if value is None:
        return ""
    if isinstance(value, (list, dict)):
        value = json.dumps(value, ensure_ascii=False)
    text = str(value)
    text = text.replace("\\", "\\\\").replace("|", "\\|").replace("<", "&lt;").replace(">", "&gt;")
    text = text.replace("$", "\\$").replace("*", "\\*").replace("_", "\\_")
    return " ".join(text.split())


def code(value):
    """A value as inline code (no escaping needed but pipes and backticks)."""
    text = value if isinstance(value, str) else json.dumps(value, ensure_ascii=False)
    text = " ".join(text.split())
    if text == "":
        return ""
    text = text.replace("|", "\\|")
    fence = "``" if "`" in text else "`"
    pad = " " if fence == "``" else ""
    return f"{fence}{pad}{text}{pad}{fence}"


CONFIG_TITLES = {
    "rimless": "The rimless wheel (`rimless` commands, campaign experiments `rimless-*`)",
    "humanoid-walk": "The humanoid walk (`humanoid walk`, `compensation`, `mismatch`, `export`; campaign `humanoid-walk`)",
    "humanoid-bench": "The stiffness bench (`humanoid bench`; campaign `humanoid-bench`)",
    "humanoid-push-recovery": "The largest recoverable push (campaign `humanoid-push-recovery`)",
}


def configuration_page(schema):
    out = ["(reference-configuration)=", "# Configuration keys", "",
           "Generated from `flexgait schema` at documentation build time. A key is set in a",
           "`--config` YAML file or with `--set key=value`; *allowed* is the domain the program checks",
           "(a value outside it is exit 2 naming the key). A default written `auto` is derived from",
           "other keys by the rule given under *derived*.", ""]
    listed = {}  # key -> the configuration whose section lists it
    for name, keys in schema["configurations"].items():
        out += [f"## {CONFIG_TITLES.get(name, name)}", ""]
        shared = sorted({listed[k["key"]] for k in keys if k["key"] in listed})
        if shared:
            out += ["It takes every key of " + ", ".join(f"`{s}`" for s in shared) + " (above), and these:", ""]
        groups = {}
        for k in keys:
            if k["key"] in listed:
                continue
            listed[k["key"]] = name
            groups.setdefault(k["key"].split(".")[0], []).append(k)
        for group, members in groups.items():
            out += [f"### {name}: `{group}.*`", "",
                    "| key | type | default | unit | allowed | doc |", "|---|---|---|---|---|---|"]
            for k in members:
                doc = cell(k.get("doc", ""))
                if k.get("derived"):
                    doc += f" *Derived (`auto`):* {cell(k['derived'])}"
                if k.get("item_fields"):
                    fields = "; ".join(
                        f"{code(f['name'])} ({cell(f.get('type'))}{', ' + cell(f.get('unit')) if f.get('unit') else ''}"
                        f"{', optional' if f.get('optional') else ''}): {cell(f.get('doc'))}"
                        for f in k["item_fields"])
                    doc += f" *Item fields:* {fields}"
                out.append(f"| {code(k['key'])} | {cell(k.get('type'))} | {code(k.get('default', ''))} | "
                           f"{cell(k.get('unit'))} | {cell(k.get('allowed'))} | {doc} |")
            out.append("")
        aliases = schema.get("aliases", {}).get(name, [])
        if aliases:
            out += [f"### {name}: aliases", "",
                    "An alias sets each of its keys to its value; it has no value of its own (a configuration",
                    "file written by the program holds its keys).", "",
                    "| alias | sets | doc |", "|---|---|---|"]
            out += [f"| {code(a['key'])} | {', '.join(code(p) for p in a['parts'])} | {cell(a.get('doc', ''))} |"
                    for a in aliases]
            out.append("")
    return "\n".join(out).rstrip() + "\n"


def results_page(schema):
    out = ["(reference-results)=", "# Result files", "",
           "Generated from `flexgait schema`: every field of the JSON summaries and every column of the",
           "CSV files the commands write, as the writers declare them.", "", "## Summaries", ""]
    for name, record in schema.get("results", {}).items():
        out += [f"### {name}", ""]
        fields = record.get("fields", []) if isinstance(record, dict) else []
        if isinstance(record, dict) and record.get("doc"):
            out += [cell(record["doc"]), ""]
        if not fields:
            out += ["(no declared fields)", ""]
            continue
        out += ["| field | type | unit | doc |", "|---|---|---|---|"]
        for f in fields:
            doc = cell(f.get("doc", ""))
            if f.get("choices"):
                doc += " Choices: " + ", ".join(code(c) for c in f["choices"])
            out.append(f"| {code(f.get('key', f.get('name', '')))} | {cell(f.get('type'))} | {cell(f.get('unit'))} | {doc} |")
        out.append("")
    out += ["## CSV files", ""]
    for name, table in schema.get("tables", {}).items():
        out += [f"### {name}", ""]
        if table.get("doc"):
            out += [cell(table["doc"]), ""]
        out += ["Columns: " + ", ".join(code(c) for c in table.get("columns", [])), ""]
        for setting, cols in table.get("present_when", {}).items():
            out += [f"Only with {code(setting)}: " + ", ".join(code(c) for c in cols), ""]
    out += ["## Runs of `flexgait reproduce`", "", "| run directory | command |", "|---|---|"]
    for run_dir, command in schema.get("reproduce", {}).items():
        out.append(f"| {code(run_dir)} | {code(command)} |")
    return "\n".join(out).rstrip() + "\n"


def subcommands(help_text):
    names, inside = [], False
    for line in help_text.splitlines():
        if re.match(r"^(SUBCOMMANDS|Subcommands):\s*$", line):
            inside = True
            continue
        if inside:
            m = re.match(r"^  (\S+)", line)
            if m:
                names.append(m.group(1))
            elif line.strip() == "":
                inside = False
    return names


def commands_page(exe):
    out = ["(reference-commands)=", "# Commands", "",
           "Generated from each command's `--help` at documentation build time.", ""]

    def walk(path, depth):
        text = run(exe, [*path, "--help"])
        title = "flexgait " + " ".join(path) if path else "flexgait"
        out.extend([("#" * min(depth, 4)) + f" `{title}`", "", "```text", text.rstrip(), "```", ""])
        for name in subcommands(text):
            walk([*path, name], depth + 1)

    walk([], 2)
    return "\n".join(out).rstrip() + "\n"


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    exe, out_dir = sys.argv[1], Path(sys.argv[2])
    out_dir.mkdir(parents=True, exist_ok=True)
    schema = json.loads(run(exe, ["schema"]))
    (out_dir / "configuration.md").write_text(configuration_page(schema), encoding="utf-8")
    (out_dir / "results.md").write_text(results_page(schema), encoding="utf-8")
    (out_dir / "commands.md").write_text(commands_page(exe), encoding="utf-8")


if __name__ == "__main__":
    main()

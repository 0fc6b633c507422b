#!/usr/bin/python3
"""Every column and field the plotting scripts ask for is one `flexgait schema` declares (issue 13:
a renamed field breaks this test, not a figure).

Usage: plot_schema_test.py FLEXGAIT_EXE PYTHON_DIR

Reads python/plot_*.py statically (ast): the files come from read_table / read_table_if_present /
read_summary calls (RUN_DIR, "FILE", "COMMAND": schema.json's "COMMAND: FILE"); the names from
the accessors column(T, NAME), has_column(T, NAME), cell(T, ROW, NAME) and field(S, NAME). A name
is checked against the table its T was assigned from in the same function, else against every
table the script reads; an f-string's placeholders match any text ("zmp_ref_{axis}" needs some
declared "zmp_ref_*"). A file name, command or column name that is not a literal fails the test,
and so does a script that reads a CSV or JSON file past the accessors (read_rows, csv, json).
"""
import ast
import glob
import json
import os
import subprocess
import sys

READERS = {"read_table", "read_table_if_present", "read_summary"}
NAME_ARG = {"column": 1, "has_column": 1, "cell": 2, "field": 1}  # position of NAME in each accessor


def literal_or_pattern(node):
    """A string literal, an f-string as a glob pattern ('*' per placeholder), or None."""
    if isinstance(node, ast.Constant) and isinstance(node.value, str):
        return node.value
    if isinstance(node, ast.JoinedStr):
        return "".join(v.value if isinstance(v, ast.Constant) else "*" for v in node.values)
    return None


def loop_values(function, name):
    """The literal values a loop variable takes: `for key, label in (("E_kinetic", "kinetic"), ...)`
    gives key the values "E_kinetic", ...; None when NAME is not such a loop variable."""
    for node in ast.walk(function):
        if not isinstance(node, (ast.For, ast.comprehension)) or not isinstance(node.iter, (ast.Tuple, ast.List)):
            continue
        target = node.target
        if isinstance(target, ast.Name) and target.id == name:
            values = [literal_or_pattern(e) for e in node.iter.elts]
        elif isinstance(target, ast.Tuple) and name in [t.id for t in target.elts if isinstance(t, ast.Name)]:
            i = [t.id if isinstance(t, ast.Name) else None for t in target.elts].index(name)
            values = [literal_or_pattern(e.elts[i]) if isinstance(e, ast.Tuple) and len(e.elts) > i else None
                      for e in node.iter.elts]
        else:
            continue
        return values if all(v is not None for v in values) else None
    return None


def call_name(node):
    return node.func.id if isinstance(node, ast.Call) and isinstance(node.func, ast.Name) else None


def root_name(node):
    """The variable an expression starts from: rows, rows.rows[-1], logs[case] -> rows, rows, logs."""
    while isinstance(node, (ast.Subscript, ast.Attribute)):
        node = node.value
    return node.id if isinstance(node, ast.Name) else None


def scan(path):
    """([(line, key or None, name pattern, table variable, function)], {function: {var: {keys}}}, problems)."""
    tree = ast.parse(open(path).read(), path)
    problems, uses, bindings, keys = [], [], {}, set()
    for function in [tree] + [n for n in ast.walk(tree) if isinstance(n, (ast.FunctionDef, ast.Lambda))]:
        scope = bindings.setdefault(id(function), {})
        for node in ast.walk(function):
            if isinstance(node, ast.Assign):
                found = {read_key(c, path, problems) for c in ast.walk(node.value) if call_name(c) in READERS}
                for target in node.targets:
                    if isinstance(target, ast.Name) and found:
                        scope.setdefault(target.id, set()).update(found)
    parents = {}
    for node in ast.walk(tree):
        for child in ast.iter_child_nodes(node):
            parents[child] = node
    for node in ast.walk(tree):
        name = call_name(node)
        if name in READERS:
            keys.add(read_key(node, path, problems))
        if name in ("read_rows", "open") or (isinstance(node, ast.Attribute) and node.attr in ("DictReader", "load")):
            problems.append(f"{path}:{node.lineno}: reads a file past the schema accessors ({name or node.attr})")
        if name not in NAME_ARG:
            continue
        if len(node.args) <= NAME_ARG[name]:
            problems.append(f"{path}:{node.lineno}: {name}() without its name argument")
            continue
        function = node
        while function in parents and not isinstance(function, (ast.FunctionDef, ast.Module)):
            function = parents[function]
        arg = node.args[NAME_ARG[name]]
        patterns = [literal_or_pattern(arg)]
        if patterns[0] is None and isinstance(arg, ast.Name):
            patterns = loop_values(function, arg.id) or [None]
        if None in patterns:
            problems.append(f"{path}:{node.lineno}: {name}() with a name that is not a literal, an f-string or a "
                            "loop over literals")
            continue
        scope = bindings.get(id(function), {})
        uses += [(node.lineno, p, scope.get(root_name(node.args[0]))) for p in patterns]
    keys.discard(None)
    return uses, keys, problems


def read_key(call, path, problems):
    file_arg, command_arg = (call.args + [None, None, None])[1:3]
    file_name = literal_or_pattern(file_arg) if file_arg is not None else None
    command = literal_or_pattern(command_arg) if command_arg is not None else None
    if not file_name or not command or "*" in file_name + command:
        problems.append(f"{path}:{call.lineno}: {call_name(call)}() without a literal file name and command")
        return None
    return f"{command}: {file_name}"


def declared(schema, key):
    if key in schema.get("tables", {}):
        return schema["tables"][key]["columns"]
    if key in schema.get("results", {}):
        return [f["key"] for f in schema["results"][key]["fields"]]
    return None


def check(schema, scripts):
    """Every problem found, one line each (empty: all names declared)."""
    import fnmatch
    problems, checked = [], 0
    for path in scripts:
        uses, keys, found = scan(path)
        problems += found
        for key in sorted(keys):
            if declared(schema, key) is None:
                problems.append(f"{path}: reads '{key}', which `flexgait schema` does not declare")
        for line, pattern, bound in uses:
            candidates = sorted(bound) if bound else sorted(keys)
            names = [n for k in candidates for n in (declared(schema, k) or [])]
            checked += 1
            if not any(fnmatch.fnmatchcase(n, pattern) for n in names):
                problems.append(f"{path}:{line}: '{pattern}' is declared in none of {', '.join(candidates)}")
    return problems, checked


SCRIPTS_USING_THE_SCHEMA = ("plot_walk.py", "plot_rimless.py", "plot_bench.py", "plot_compensation.py")


def main(argv):
    if len(argv) != 3:
        sys.exit(__doc__)
    exe, python_dir = argv[1], argv[2]
    schema = json.loads(subprocess.run([exe, "schema"], check=True, capture_output=True, text=True).stdout)
    scripts = [os.path.join(python_dir, s) for s in SCRIPTS_USING_THE_SCHEMA]
    missing = [s for s in scripts if not os.path.exists(s)]
    problems, checked = check(schema, [s for s in scripts if s not in missing])
    problems += [f"{s}: no such script" for s in missing]
    # A script reading CSV or JSON that is not in the list above is left unchecked: name it.
    others = sorted(set(glob.glob(os.path.join(python_dir, "plot_*.py"))) - set(scripts))
    print(f"checked {checked} column/field names in {len(scripts)} scripts; not yet on the schema: "
          + ", ".join(os.path.basename(o) for o in others))
    for p in problems:
        print(p)
    return 1 if problems or checked == 0 else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))

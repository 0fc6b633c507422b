#!/usr/bin/python3
"""Every column and field the plotting scripts ask for is one `flexgait schema` declares
(a renamed field breaks this test, not a figure).

Usage: plot_schema_test.py FLEXGAIT_EXE PYTHON_DIR   (the report's names: PYTHON_DIR/../data/report/references.yaml)

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

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "python"))
from flexgait_schema import SchemaError, declared_names, names_asked  # noqa: E402

READERS = {"read_table", "read_table_if_present", "read_summary"}
NAME_ARG = {"column": 1, "has_column": 1, "cell": 2, "field": 1, "items": 1}  # position of NAME in each accessor


def literal_or_pattern(node):
    """A string literal, an f-string as a glob pattern ('*' per placeholder), or None."""
    if isinstance(node, ast.Constant) and isinstance(node.value, str):
        return node.value
    if isinstance(node, ast.JoinedStr):
        return "".join(v.value if isinstance(v, ast.Constant) else "*" for v in node.values)
    return None


def own_nodes(function):
    """The nodes of a function's (or the module's) own body, not those of the functions inside it."""
    todo = list(ast.iter_child_nodes(function))
    while todo:
        node = todo.pop()
        yield node
        if not isinstance(node, ast.FunctionDef):
            todo.extend(ast.iter_child_nodes(node))


def loop_values(function, name):
    """The literal values a loop variable takes: `for key, label in (("E_kinetic", "kinetic"), ...)`
    gives key the values "E_kinetic", ...; None when NAME is not such a loop variable."""
    for node in own_nodes(function):
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


def argument_values(tree, function, name):
    """The literal values a parameter NAME of FUNCTION takes at the module's calls of it
    (draw_branch(ax, rows, "thetad") gives column "thetad"); None when some call passes another."""
    if not isinstance(function, ast.FunctionDef):
        return None
    params = [a.arg for a in function.args.args]
    if name not in params:
        return None
    index, values = params.index(name), []
    for call in ast.walk(tree):
        if call_name(call) != function.name:
            continue
        given = [k.value for k in call.keywords if k.arg == name]
        given += call.args[index:index + 1]
        values += [literal_or_pattern(g) for g in given[:1]]
    return values if values and None not in values else None


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
    for function in [tree] + [n for n in ast.walk(tree) if isinstance(n, ast.FunctionDef)]:
        scope = bindings.setdefault(id(function), {})
        for node in own_nodes(function):
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
        if name in ("read_rows", "open"):
            files = {literal_or_pattern(n) for n in ast.walk(node) if isinstance(n, ast.Constant)}
            allowed = files & set(NOT_YET_IN_THE_SCHEMA.get(os.path.basename(path), ()))
            if not allowed:
                problems.append(f"{path}:{node.lineno}: reads a file past the schema accessors ({name})")
        if name not in NAME_ARG:
            continue
        if len(node.args) <= NAME_ARG[name]:
            problems.append(f"{path}:{node.lineno}: {name}() without its name argument")
            continue
        functions, up = [], node  # the enclosing functions, innermost first, then the module
        while up in parents:
            up = parents[up]
            if isinstance(up, (ast.FunctionDef, ast.Module)):
                functions.append(up)
        arg = node.args[NAME_ARG[name]]
        patterns = [literal_or_pattern(arg)]
        if patterns[0] is None and isinstance(arg, ast.Name):
            patterns = next((v for f in functions for v in (loop_values(f, arg.id), argument_values(tree, f, arg.id))
                             if v), [None])
        if None in patterns:
            problems.append(f"{path}:{node.lineno}: {name}() with a name that is not a literal, an f-string, a "
                            "loop over literals or a parameter given literals")
            continue
        table = root_name(node.args[0])
        bound = next((bindings[id(f)][table] for f in functions if table in bindings.get(id(f), {})), None)
        uses += [(node.lineno, p, bound) for p in patterns]
    keys.discard(None)
    return uses, keys, problems


def read_key(call, path, problems):
    file_arg, command_arg = (call.args + [None, None, None])[1:3]
    file_arg = next((k.value for k in call.keywords if k.arg == "as_file"), file_arg)
    file_name = literal_or_pattern(file_arg) if file_arg is not None else None
    command = literal_or_pattern(command_arg) if command_arg is not None else None
    if not file_name or not command or "*" in file_name + command:
        problems.append(f"{path}:{call.lineno}: {call_name(call)}() without a literal file name and command")
        return None
    return f"{command}: {file_name}"


def declared(schema, key):
    """The names declared for "COMMAND: FILE" (a result's list items' fields too), or None."""
    try:
        return declared_names(schema, key)
    except SchemaError:
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


def check_report(schema, references_path):
    """The report's names (data/report/references.yaml, which python/report.py reads): each row's
    run is a run of `flexgait reproduce` (schema "reproduce"), and each value's JSON key (its first
    token) or CSV columns are declared for that run's command and file, where the schema declares
    the file. Returns (problems, names checked, files without a schema entry)."""
    import yaml
    with open(references_path) as f:
        references = yaml.safe_load(f)
    runs = schema.get("reproduce", {})
    problems, checked, unchecked = [], 0, set()
    for row in references["rows"]:
        where = f"{references_path}: row {row['id']}"
        if row["run"] not in runs:
            problems.append(f"{where}: run '{row['run']}' is not a run of `flexgait reproduce`")
            continue
        for name, spec in row["values"].items():
            key = f"{runs[row['run']]}: {spec['file']}"
            names = declared(schema, key)
            if names is None:
                unchecked.add(key)
                continue
            for a in names_asked(spec):
                checked += 1
                if a not in names:
                    problems.append(f"{where}: value {name}: '{a}' is not declared for '{key}'")
    return problems, checked, sorted(unchecked)


SCRIPTS_USING_THE_SCHEMA = ("plot_walk.py", "plot_rimless.py", "plot_bench.py", "plot_compensation.py",
                            "plot_analysis.py", "plot_sweep.py", "plot_maps.py", "plot_mismatch.py")
# Files these scripts still read by name without a schema entry (each a known gap, named in the
# test's output): robustness.csv's writer finds a fixed point before it writes its header; the
# basin's summary.json is built by hand in src/cli/rimless_map_commands.cpp.
NOT_YET_IN_THE_SCHEMA = {"plot_analysis.py": ("robustness.csv",), "plot_maps.py": ("summary.json",)}


# The check itself must be able to fail: a script asking for an undeclared column, one naming an
# undeclared file, and one reading past the accessors.
SELF_CHECK = """
from flexgait_plotting import column, read_rows, read_table


def main(run_dir):
    log = read_table(run_dir, "log.csv", "humanoid walk")
    column(log, "no_such_column")
    column(read_table(run_dir, "nothing.csv", "humanoid walk"), "t")
    read_rows("log.csv")
"""


def self_check(schema):
    import tempfile
    with tempfile.TemporaryDirectory() as d:
        path = os.path.join(d, "plot_self_check.py")
        with open(path, "w") as f:
            f.write(SELF_CHECK)
        problems, _ = check(schema, [path])
    expected = ("'no_such_column' is declared in none of humanoid walk: log.csv",
                "reads 'humanoid walk: nothing.csv'", "reads a file past the schema accessors")
    return [f"self-check: the check did not report: {e}" for e in expected if not any(e in p for p in problems)]


def runtime_check():
    """The accessors at run time: a column the schema beside the run does not declare, and a declared
    one the file lacks, each fail naming the file and the column."""
    import tempfile
    import flexgait_plotting as fp
    problems = []
    with tempfile.TemporaryDirectory() as d:
        run = os.path.join(d, "run")
        os.mkdir(run)
        with open(os.path.join(d, "schema.json"), "w") as f:
            json.dump({"tables": {"humanoid walk: log.csv": {"columns": ["t", "com_x"]}}}, f)
        with open(os.path.join(run, "log.csv"), "w") as f:
            f.write("t\n0.5\n")
        table = fp.read_table(run, "log.csv", "humanoid walk")
        if fp.column(table, "t") != [0.5]:
            problems.append("runtime check: column() did not read the column")
        for name, expected in (("com_y", "column 'com_y' is not declared"), ("com_x", "no column 'com_x' in the file")):
            try:
                fp.column(table, name)
                problems.append(f"runtime check: column(table, '{name}') did not fail")
            except SchemaError as e:
                if expected not in str(e) or "log.csv" not in str(e):
                    problems.append(f"runtime check: column(table, '{name}') failed with '{e}'")
    return problems


def main(argv):
    if len(argv) != 3:
        sys.exit(__doc__)
    exe, python_dir = argv[1], argv[2]
    schema = json.loads(subprocess.run([exe, "schema"], check=True, capture_output=True, text=True).stdout)
    scripts = [os.path.join(python_dir, s) for s in SCRIPTS_USING_THE_SCHEMA]
    missing = [s for s in scripts if not os.path.exists(s)]
    problems, checked = check(schema, [s for s in scripts if s not in missing])
    problems += [f"{s}: no such script" for s in missing]
    problems += self_check(schema) + runtime_check()
    report_problems, report_checked, report_unchecked = check_report(
        schema, os.path.join(os.path.dirname(os.path.abspath(python_dir)), "data", "report", "references.yaml"))
    problems += report_problems
    # A script reading CSV or JSON that is not in the list above is left unchecked: name it.
    others = sorted(set(glob.glob(os.path.join(python_dir, "plot_*.py"))) - set(scripts))
    print(f"checked {checked} column/field names in {len(scripts)} scripts; not yet on the schema: "
          + ", ".join(os.path.basename(o) for o in others) + "; files read unchecked: "
          + ", ".join(f"{s}: {', '.join(f)}" for s, f in NOT_YET_IN_THE_SCHEMA.items()))
    print(f"checked {report_checked} names the report reads (references.yaml); files it reads without a schema "
          f"entry: {', '.join(report_unchecked)}")
    for p in problems:
        print(p)
    return 1 if problems or checked == 0 or report_checked == 0 else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))

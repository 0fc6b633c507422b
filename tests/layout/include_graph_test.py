#!/usr/bin/env python3
"""The folders of src/flexgait, their includes and their namespaces (one library per folder).

Checks, over every .hpp and .cpp under src/flexgait:
  - the graph folder -> folder of the includes "flexgait/<folder>/..." has no cycle;
  - MuJoCo (<mujoco/...>) is included only under twin/, and under twin/ by no installed header
    (only twin/detail/ and .cpp files);
  - the controller's folders (robot, walking, compensation) include nothing of twin/, where the
    twin's truth lives (plant_params.hpp: its stiffness, sensors, faults, floor; disturbance.hpp;
    terrain.hpp; sensor_faults.hpp);
  - one namespace per library: no namespace is opened by two folders (a block that only
    forward-declares another library's types does not count).
Usage: include_graph_test.py SOURCE_DIR. Prints each violation; exit 1 if any.
"""
import pathlib
import re
import sys

INCLUDE = re.compile(r'^\s*#\s*include\s*[<"]([^>"]+)[>"]', re.M)
CONTROLLER = {"robot", "walking", "compensation"}
NAMESPACE = re.compile(r'^namespace (flexgait(?:::\w+)*) \{', re.M)
FORWARD_ONLY = re.compile(r'^namespace flexgait(?:::\w+)* \{\n(?:(?:enum class|enum|struct|class) \w+(?: : [\w:]+)?;[^\n]*\n)+\}', re.M)


def top_namespace(name: str) -> str:
    """flexgait::twin::detail -> flexgait::twin; flexgait -> flexgait."""
    return "::".join(name.split("::")[:2])


def main(source: pathlib.Path) -> int:
    root = source / "src" / "flexgait"
    edges: dict[str, set[str]] = {}
    problems = []
    owners: dict[str, set[str]] = {}
    for path in sorted(root.rglob("*")):
        if path.suffix not in (".hpp", ".cpp"):
            continue
        rel = path.relative_to(root)
        folder = rel.parts[0]
        if len(rel.parts) == 1:
            continue  # version.hpp.in and the like
        edges.setdefault(folder, set())
        text = path.read_text(encoding="utf-8")
        for ns in NAMESPACE.findall(FORWARD_ONLY.sub("", text)):
            owners.setdefault(top_namespace(ns), set()).add(folder)
        for name in INCLUDE.findall(text):
            if name.startswith("mujoco/"):
                installed = path.suffix == ".hpp" and "detail" not in rel.parts
                if folder != "twin" or installed:
                    problems.append(f"{rel}: includes <{name}> (MuJoCo belongs in twin/*.cpp or twin/detail/)")
            parts = name.split("/")
            if len(parts) >= 3 and parts[0] == "flexgait" and (root / parts[1]).is_dir():
                if parts[1] != folder:
                    edges[folder].add(parts[1])
                if folder in CONTROLLER and parts[1] == "twin":
                    problems.append(f"{rel}: the controller's folder {folder}/ includes {name}")
    for ns, folders in sorted(owners.items()):
        if len(folders) > 1:
            problems.append(f"namespace {ns} is opened by {len(folders)} folders: {', '.join(sorted(folders))}")
    # A cycle: depth-first search with colours.
    state: dict[str, int] = {}
    stack: list[str] = []

    def visit(node: str) -> None:
        state[node] = 1
        stack.append(node)
        for nxt in sorted(edges.get(node, ())):
            if state.get(nxt) == 1:
                cycle = stack[stack.index(nxt):] + [nxt]
                problems.append("folder cycle: " + " -> ".join(cycle))
            elif nxt not in state:
                visit(nxt)
        stack.pop()
        state[node] = 2

    for node in sorted(edges):
        if node not in state:
            visit(node)
    for p in problems:
        print(p)
    print(f"{len(edges)} folders, {sum(len(v) for v in edges.values())} folder dependencies, {len(problems)} problems")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(pathlib.Path(sys.argv[1])))

#!/usr/bin/env python3
"""The folders of src/flexgait and their includes (issue 16, "The layout shows the architecture").

Checks, over every .hpp and .cpp under src/flexgait:
  - the graph folder -> folder of the includes "flexgait/<folder>/..." has no cycle;
  - MuJoCo (<mujoco/...>) is included only under twin/, and under twin/ by no installed header
    (only twin/detail/ and .cpp files);
  - the controller's folders (robot, walking, compensation) include nothing of twin/, where the
    twin's truth lives (plant_params.hpp: its stiffness, sensors, faults, floor; disturbance.hpp;
    terrain.hpp; sensor_faults.hpp).
Usage: include_graph_test.py SOURCE_DIR. Prints each violation; exit 1 if any.
"""
import pathlib
import re
import sys

INCLUDE = re.compile(r'^\s*#\s*include\s*[<"]([^>"]+)[>"]', re.M)
CONTROLLER = {"robot", "walking", "compensation"}


def main(source: pathlib.Path) -> int:
    root = source / "src" / "flexgait"
    edges: dict[str, set[str]] = {}
    problems = []
    for path in sorted(root.rglob("*")):
        if path.suffix not in (".hpp", ".cpp"):
            continue
        rel = path.relative_to(root)
        folder = rel.parts[0]
        if len(rel.parts) == 1:
            continue  # version.hpp.in and the like
        edges.setdefault(folder, set())
        for name in INCLUDE.findall(path.read_text(encoding="utf-8")):
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

#!/usr/bin/env python3
"""The test tree mirrors src/: a test file per source file with logic.

Checks, for every .cpp under src/flexgait (detail/ folders included):
  - tests/<dir>/<name>_test.cpp exists for src/flexgait/<dir>/<name>.cpp, unless the file is in
    NO_LOGIC below;
  - that test file is built: tests/CMakeLists.txt names it (a file no program compiles tests nothing);
  - every NO_LOGIC entry is still a source file without a test of its own (a stale entry fails).
Usage: mirror_test.py SOURCE_DIR. Prints each violation; exit 1 if any.
"""
import pathlib
import re
import sys

# Source files without logic of their own, exempt from the rule: "<dir>/<name>.cpp" -> why.
# Each entry needs a reason a reviewer can check (data only, generated, a forwarding shim).
# Today every source file has a test file; add here only what truly has nothing to test.
NO_LOGIC: dict[str, str] = {}


def main(source: pathlib.Path) -> int:
    src = source / "src" / "flexgait"
    tests = source / "tests"
    cmake = (tests / "CMakeLists.txt").read_text(encoding="utf-8")
    built = set(re.findall(r"[\w/]+_test\.cpp", cmake))
    problems = []
    for path in sorted(src.rglob("*.cpp")):
        rel = path.relative_to(src)
        key = rel.as_posix()
        test = rel.parent / f"{rel.stem}_test.cpp"
        exists = (tests / test).is_file()
        if key in NO_LOGIC:
            if exists:
                problems.append(f"{key}: in NO_LOGIC but tests/{test.as_posix()} exists; remove the entry")
            continue
        if not exists:
            problems.append(f"{key}: no tests/{test.as_posix()} (a test file per source file with logic, "
                            "or an entry in NO_LOGIC of tests/layout/mirror_test.py saying why not)")
        elif test.as_posix() not in built:
            problems.append(f"tests/{test.as_posix()}: not built; add it to a program in tests/CMakeLists.txt")
    for key in sorted(NO_LOGIC):
        if not (src / key).is_file():
            problems.append(f"{key}: in NO_LOGIC but not a source file any more; remove the entry")
    for p in problems:
        print(p)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(pathlib.Path(sys.argv[1])))

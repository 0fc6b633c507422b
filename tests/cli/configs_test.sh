#!/usr/bin/env bash
# Bundled configurations by name: `flexgait configs` lists each configs/*.yaml with the first line
# of its leading comment, and `--config NAME` (no directory, no extension) loads configs/NAME.yaml
# from any directory, giving the same run as the path does; a name that is neither a file nor a
# bundled configuration is exit 2 naming it and the names there are.
# Usage: configs_test.sh FLEXGAIT_EXE SOURCE_DIR
set -u
exe=$1
src=$2
source "$(dirname "$0")/harness.sh"

mkdir -p "$work/elsewhere"
cd "$work/elsewhere" || exit 1

"$exe" configs >"$work/list" 2>"$work/list.err"
check "configs exits 0" test $? -eq 0
for f in "$src"/configs/*.yaml; do
  name=$(basename "$f" .yaml)
  first=$(grep -m1 '^#' "$f" | sed 's/^#[[:space:]]*//')
  check "configs lists $name with its description" grep -qF "$name  " "$work/list"
  check "configs gives $name's first comment line" grep -qF -- "$first" "$work/list"
done
check "configs: one line per file" test "$(wc -l <"$work/list")" -eq "$(ls "$src"/configs/*.yaml | wc -l)"
"$exe" configs --paths >"$work/paths"
check "configs --paths names the source tree's file (uninstalled build)" \
  grep -qF "$src/configs/rimless.yaml" "$work/paths"

# The same run by name and by path: identical summary.json bytes.
"$exe" rimless simulate --config rimless --steps 2 --no-plot --out by-name >/dev/null 2>&1
check "--config rimless from another directory exits 0" test $? -eq 0
"$exe" rimless simulate --config "$src/configs/rimless.yaml" --steps 2 --no-plot --out by-path >/dev/null 2>&1
check "by name and by path: the same summary.json" cmp -s by-name/summary.json by-path/summary.json
check "by name and by path: the same config.yaml" cmp -s by-name/config.yaml by-path/config.yaml
# A local file wins over a bundled name: a file named like a config, in the working directory.
printf 'rimless:\n  K: 2000\n' >rimless
"$exe" rimless simulate --config rimless --steps 1 --no-plot --out local >/dev/null 2>&1
check "a file in the working directory is read as given" grep -q "K: 2000" local/config.yaml
rm -f rimless

# Bad names: exit 2, one line naming the value and the bundled names, nothing written.
for bad in no-such-config rimless.yml ./rimless configs/rimless; do
  "$exe" rimless simulate --config "$bad" --no-plot --out "never" >"$work/out" 2>"$work/err"
  code=$?
  check "--config $bad: exit 2 (got $code)" test "$code" -eq 2
  check "--config $bad: names the value" grep -qF -- "'$bad'" "$work/err"
  check "--config $bad: lists the bundled names" grep -qF "walk-dynamic" "$work/err"
  check "--config $bad: one line" test "$(wc -l <"$work/err")" -eq 1
  check "--config $bad: nothing written" test ! -e never
done
# The humanoid commands (loaded from the command module) take names too.
"$exe" humanoid export --config walk-dynamic --format mjcf --out twin.xml >/dev/null 2>&1
check "humanoid export --config walk-dynamic" test -s twin.xml
"$exe" humanoid walk --config no-such-walk --no-plot --out never >/dev/null 2>"$work/err"
check "humanoid walk --config no-such-walk: exit 2" test $? -eq 2

echo "$passed passed, $failed failed"
test "$failed" -eq 0

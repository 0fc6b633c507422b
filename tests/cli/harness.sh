# Shared by the command-line test scripts (sourced): a scratch directory $work removed at exit, and
# check NAME CONDITION... counting $passed and $failed (printing FAIL: NAME when CONDITION fails).
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
passed=0
failed=0
check() {  # check NAME CONDITION...
  local name=$1
  shift
  if "$@"; then passed=$((passed + 1)); else failed=$((failed + 1)); echo "FAIL: $name"; fi
}

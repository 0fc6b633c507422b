#!/usr/bin/env bash
# Output targets that are not regular files (run directories: not directories) are refused before
# any work, exit 2 with one line naming --out, the path and its kind, the target left as it was:
# a FIFO, a socket, a symbolic link to a FIFO, a directory, /dev/null (a root process renaming over
# it would replace the system's /dev/null), a run directory holding a FIFO where a file would go.
# Also the projected size of `rimless simulate`'s log (sim.max_log_bytes). Usage:
# output_targets_test.sh FLEXGAIT_EXE
set -u
exe=$1
source "$(dirname "$0")/harness.sh"

# expect_refused NAME NEEDLE ARGS...: exit 2, one line on stderr naming NEEDLE, no temporary file
# left in $work or in /dev (AtomicFileWriter's ".NAME.tmp-PID-XXXXXX").
expect_refused() {
  local name=$1 needle=$2
  shift 2
  timeout 120 "$exe" "$@" >"$work/stdout" 2>"$work/stderr"
  local code=$?
  check "$name: exit code 2 (got $code)" test "$code" -eq 2
  check "$name: message names '$needle': $(head -c 1000 "$work/stderr")" grep -qF -- "$needle" "$work/stderr"
  check "$name: one line on stderr" test "$(wc -l <"$work/stderr")" -eq 1
  check "$name: no temporary file left" test -z "$(find "$work" /dev -maxdepth 2 -name '.*.tmp-*' 2>/dev/null)"
}

mkfifo "$work/fifo"
ln -s "$work/fifo" "$work/link_to_fifo"
/usr/bin/python3 -c "import socket, sys; socket.socket(socket.AF_UNIX).bind(sys.argv[1])" "$work/sock"
mkdir "$work/a_dir"

# humanoid export writes one file (--out FILE).
expect_refused export-fifo "--out: $work/fifo is a FIFO (named pipe), not a regular file" \
  humanoid export --out "$work/fifo"
check "export-fifo: still a FIFO" test -p "$work/fifo"
expect_refused export-dev-null "--out: /dev/null is a character device, not a regular file" \
  humanoid export --format urdf --out /dev/null
check "export-dev-null: /dev/null still a character device" test -c /dev/null
check "export-dev-null: nothing printed before the refusal" test ! -s "$work/stdout"
expect_refused export-link "is a symbolic link to a FIFO (named pipe)" humanoid export --out "$work/link_to_fifo"
check "export-link: still a link to the FIFO" test -L "$work/link_to_fifo" -a -p "$work/fifo"
expect_refused export-socket "$work/sock is a socket" humanoid export --out "$work/sock"
check "export-socket: still a socket" test -S "$work/sock"
expect_refused export-directory "$work/a_dir is a directory" humanoid export --out "$work/a_dir"
check "export-directory: still an empty directory" test -z "$(ls -A "$work/a_dir")"
expect_refused schema-fifo "--out: $work/fifo is a FIFO" schema --out "$work/fifo"
expect_refused schema-dev-null "--out: /dev/null is a character device" schema --out /dev/null
check "schema-dev-null: /dev/null still a character device" test -c /dev/null
# A regular file is replaced whole.
printf 'old\n' >"$work/robot.xml"
timeout 120 "$exe" humanoid export --out "$work/robot.xml" >/dev/null 2>&1
check "export over a regular file: exit 0" test $? -eq 0
check "export over a regular file: replaced" grep -q "<mujoco" "$work/robot.xml"

# Run directories (--out DIR).
quick=(rimless simulate --set sim.model=rigid --steps 1 --no-plot)
expect_refused run-dir-fifo "--out: cannot make the run directory $work/fifo: it is a FIFO (named pipe), not a directory" "${quick[@]}" --out "$work/fifo"
expect_refused run-dir-dev-null "--out: cannot make the run directory /dev/null: it is a character device, not a directory" "${quick[@]}" --out /dev/null
check "run-dir-dev-null: /dev/null still a character device" test -c /dev/null
mkdir "$work/run" && mkfifo "$work/run/log.csv"
expect_refused run-dir-holding-fifo "--out: cannot use the run directory $work/run: it holds log.csv, which is a FIFO (named pipe)" "${quick[@]}" \
  --out "$work/run"
check "run-dir-holding-fifo: nothing written" test "$(ls -A "$work/run")" = log.csv
check "run-dir-holding-fifo: still a FIFO" test -p "$work/run/log.csv"

# The log's projected size: sample_dt = 1e-6 s over the default 120 s is ~5e10 bytes.
expect_refused log-too-large "--set: key 'sim.sample_dt' = 1e-06 s: the log could reach" \
  rimless simulate --set sim.sample_dt=1e-6 --no-plot --out "$work/big"
check "log-too-large: names the key that lifts it" grep -q "sim.max_log_bytes raised to at least" "$work/stderr"
check "log-too-large: nothing written" test ! -e "$work/big"
# The key moves the cap both ways: sample_dt = 1e-4 s over one step's limit (sim.max_step_time,
# 10 s) projects 400 x 1e5 = 4e7 bytes.
expect_refused log-cap-lowered "above sim.max_log_bytes = 1e+07" rimless simulate --set sim.model=rigid --steps 1 \
  --set sim.sample_dt=1e-4 --set sim.max_log_bytes=1e7 --no-plot --out "$work/capped"
check "log-cap-lowered: nothing written" test ! -e "$work/capped"
timeout 120 "$exe" rimless simulate --set sim.model=rigid --steps 1 --set sim.sample_dt=1e-4 --no-plot \
  --out "$work/fine" >/dev/null 2>"$work/stderr"
check "sample_dt = 1e-4 under the default cap: exit 0 ($(head -c 300 "$work/stderr"))" test $? -eq 0
rows=$(($(wc -l <"$work/fine/log.csv") - 1))
check "the log's rows within the projection's 400 bytes each" test "$(stat -c %s "$work/fine/log.csv")" -le $((400 * rows))

echo "output targets: $passed passed, $failed failed"
[ "$failed" -eq 0 ]

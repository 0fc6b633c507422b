#!/usr/bin/env bash
# Pictures from the command line: `rimless simulate` writes replay.html; `flexgait render --run`
# draws it to PNG frames and video.mp4 (ffmpeg, when present); bad input is exit 2 with one line
# naming the option and nothing written: --size 0x0, an unknown --camera, a run directory without
# a replay. Usage: render_test.sh FLEXGAIT_EXE
set -u
exe=$1
source "$(dirname "$0")/harness.sh"

# expect_usage_error NAME NEEDLE ARGS...: exit 2, one line on stderr naming NEEDLE, no $work/never-NAME
expect_usage_error() {
  local name=$1 needle=$2
  shift 2
  timeout 60 "$exe" "$@" >/dev/null 2>"$work/stderr"
  local code=$?
  check "$name: exit code 2 (got $code)" test "$code" -eq 2
  check "$name: message names '$needle': $(head -c 1000 "$work/stderr")" grep -qF -- "$needle" "$work/stderr"
  check "$name: one line on stderr" test "$(wc -l <"$work/stderr")" -eq 1
  check "$name: nothing written" test ! -e "$work/never-$name"
}
expect_usage_error walk-size-zero "--size '0x0'" humanoid walk --render --size 0x0 --out "$work/never-walk-size-zero"
expect_usage_error walk-size-too-big "--size '1920x1080'" humanoid walk --render --size 1920x1080 --out "$work/never-walk-size-too-big"
expect_usage_error walk-size-text "--size 'big'" humanoid walk --render --size big --out "$work/never-walk-size-text"
expect_usage_error walk-camera "--camera 'top': expected side, follow or front" humanoid walk --render --camera top \
  --out "$work/never-walk-camera"
mkdir -p "$work/empty"
expect_usage_error render-no-replay "--run '$work/empty': no replay.html" render --run "$work/empty"
expect_usage_error render-size "--size '0x0'" render --run "$work/empty" --size 0x0

# A short rimless run, drawn small.
"$exe" rimless simulate --steps 2 --no-plot --out "$work/wheel" >/dev/null
check "rimless simulate writes replay.html" test -s "$work/wheel/replay.html"
echo "<html>no data</html>" >"$work/empty/replay.html"
expect_usage_error render-bad-replay "replay.html cannot be read" render --run "$work/empty"
"$exe" render --run "$work/wheel" --size 160x90 --fps 10 >"$work/out" 2>&1
code=$?
check "render exit 0 (got $code): $(head -c 500 "$work/out")" test "$code" -eq 0
check "render writes frames" test -s "$work/wheel/frames/frame_00000.png"
frames=$(find "$work/wheel/frames" -name 'frame_*.png' | wc -l)
# 2 steps take ~0.75 s: 10 frames per second of simulated time, the first at t = 0.
check "about 10 frames per simulated second (got $frames)" test "$frames" -ge 6 -a "$frames" -le 12
if command -v ffmpeg >/dev/null; then check "render writes video.mp4" test -s "$work/wheel/video.mp4"; fi

echo "render: $passed passed, $failed failed"
[ "$failed" -eq 0 ]

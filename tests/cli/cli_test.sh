#!/usr/bin/env bash
# Command-line behaviour: help and version, bad input (exit 2, one line naming the key, the value
# and what is allowed, nothing written), a run directory with every file, identical bytes on a
# rerun. Usage: cli_test.sh FLEXGAIT_EXE SOURCE_DIR
set -u
exe=$1
src=$2
source "$(dirname "$0")/harness.sh"
# expect_usage_error NAME NEEDLE ARGS...: exit code 2, stderr names NEEDLE, no run directory.
expect_usage_error() {
  local name=$1 needle=$2
  shift 2
  local out="$work/never-$name"
  timeout 120 "$exe" "$@" --out "$out" --no-plot >"$work/stdout" 2>"$work/stderr"
  local code=$?
  check "$name: exit code 2 (got $code)" test "$code" -eq 2
  check "$name: message names '$needle': $(head -c 2000 "$work/stderr")" grep -qF -- "$needle" "$work/stderr"
  check "$name: one line on stderr" test "$(wc -l <"$work/stderr")" -eq 1
  check "$name: nothing written" test ! -e "$out"
}

"$exe" --help >"$work/help" 2>&1
check "--help exits 0" test $? -eq 0
check "--help lists rimless" grep -q rimless "$work/help"
"$exe" rimless simulate --help >"$work/help2" 2>&1
check "simulate --help documents --omega0 with units" grep -q "initial angular velocity (rad/s)" "$work/help2"
"$exe" --version >"$work/version" 2>&1
check "--version" grep -q "^flexgait [0-9]" "$work/version"
# The commands that need MuJoCo are a module loaded on demand (src/cli/command_module.hpp): a
# rimless command starts without MuJoCo and its libraries; --help and a humanoid command load it.
LD_DEBUG=files "$exe" rimless simulate --help >/dev/null 2>"$work/loaded"
check "rimless loads no MuJoCo" bash -c "! grep -q libmujoco '$work/loaded'"
check "rimless loads no OSMesa" bash -c "! grep -q libOSMesa '$work/loaded'"
LD_DEBUG=files "$exe" humanoid walk --help >/dev/null 2>"$work/loaded"
check "humanoid loads MuJoCo" grep -q libmujoco "$work/loaded"
for command in rimless humanoid campaign reproduce schema; do
  check "--help lists $command" grep -qE "^  $command( |$)" "$work/help"
done

expect_usage_error unknown-key "rimless.KK" rimless simulate --set rimless.KK=5
expect_usage_error out-of-range "rimless.K" rimless simulate --set rimless.K=-1
expect_usage_error nan "rimless.mu_s" rimless simulate --set rimless.mu_s=nan
expect_usage_error wrong-type "rimless.legs" rimless simulate --set rimless.legs=ten
expect_usage_error cross-check "rimless.mu_k" rimless simulate --set rimless.mu_s=0.2 --set rimless.mu_k=0.3
expect_usage_error beta-range "initial.beta" rimless simulate --set initial.beta=0.5
expect_usage_error stribeck-velocity "rimless.stribeck_velocity" rimless simulate --set rimless.friction=stribeck --set rimless.stribeck_velocity=0
expect_usage_error stribeck-exponent "rimless.stribeck_exponent" rimless simulate --set rimless.friction=stribeck --set rimless.stribeck_exponent=-1
expect_usage_error stribeck-viscous "rimless.viscous" rimless simulate --set rimless.friction=stribeck --set rimless.viscous=-0.1
expect_usage_error stribeck-key-with-coulomb "rimless.viscous" rimless simulate --set rimless.viscous=0.5
expect_usage_error stribeck-velocity-with-coulomb "rimless.stribeck_velocity" rimless fixed-point --set rimless.stribeck_velocity=0.3
expect_usage_error missing-file "no/such.yaml" rimless simulate --config no/such.yaml
printf 'rimless:\n  K: 1000\n  mux: 0.5\n' >"$work/typo.yaml"
expect_usage_error typo-in-file "typo.yaml:3" rimless simulate --config "$work/typo.yaml"
expect_usage_error bad-model "--model" rimless simulate --model soft
# YAML read with limits: each refusal names the file and the line.
printf 'a: &a\n  b: *a\n' >"$work/recursive.yaml"
expect_usage_error recursive-alias "recursive.yaml:2: a recursive alias" rimless simulate --config "$work/recursive.yaml"
{ echo 'l0: &l0 {a: 1, b: 1}'; for i in $(seq 1 30); do echo "l$i: &l$i {a: *l$((i - 1)), b: *l$((i - 1))}"; done; } \
  >"$work/bomb.yaml"
expect_usage_error alias-bomb "aliases expand to more than" rimless simulate --config "$work/bomb.yaml"
printf 'rimless:\n  K: 1000\n  K: 2000\n' >"$work/dup.yaml"
expect_usage_error duplicate-key "dup.yaml:3: key 'K' given twice" rimless simulate --config "$work/dup.yaml"
printf 'rimless:\n  K: 1000\n---\nrimless:\n  K: 2000\n' >"$work/docs.yaml"
expect_usage_error extra-document "docs.yaml:3: a second YAML document" rimless simulate --config "$work/docs.yaml"
printf '? [rimless, K]\n: 1\n' >"$work/complex.yaml"
expect_usage_error complex-key "complex.yaml:1: a key must be a plain name" rimless simulate --config "$work/complex.yaml"
mkfifo "$work/fifo.yaml"
expect_usage_error fifo-config "fifo.yaml: is not a regular file" rimless simulate --config "$work/fifo.yaml"
head -c 2000000 /dev/zero | tr '\0' '#' >"$work/huge.yaml"
expect_usage_error huge-config "huge.yaml: larger than" rimless simulate --config "$work/huge.yaml"
# One line whatever the value holds: control characters escaped, long values cut.
expect_usage_error newline-in-value 'rimless.K' rimless simulate --set "rimless.K=1$(printf '\n')2x"
expect_usage_error long-value '(100000 bytes)' rimless simulate --set "rimless.K=$(head -c 100000 /dev/zero | tr '\0' 5)"
expect_usage_error unknown-command "unknown command 'fly'" fly
expect_usage_error unknown-subcommand "unknown command 'fly'" rimless fly
# Every option checked as --set is, named as given, before anything is written.
expect_usage_error steps-empty "--steps: key 'sim.steps' = ''" rimless simulate --steps ''
expect_usage_error steps-negative "--steps: key 'sim.steps' = '-1'" rimless simulate --steps -1
expect_usage_error omega0-nan "--omega0: key 'initial.omega' = 'nan'" rimless simulate --omega0 nan
expect_usage_error cross-check-names-set "--set: key 'rimless.mu_k'" rimless simulate --set rimless.mu_s=0.2 --set rimless.mu_k=0.3
printf 'rimless:\n  mu_s: 0.2\n  mu_k: 0.3\n' >"$work/mu.yaml"
expect_usage_error cross-check-names-file "mu.yaml:3: key 'rimless.mu_k'" rimless simulate --config "$work/mu.yaml"
expect_usage_error energy-negative-mu "--mu: key 'analysis.energy.mu[0]' = '-1'" rimless analysis energy --mu -1
expect_usage_error energy-empty-mu "--mu: key 'analysis.energy.mu' = '[]'" rimless analysis energy --mu ''
expect_usage_error energy-empty-mu-field "--mu: key 'analysis.energy.mu[1]' = ''" rimless analysis energy --mu 0.6,,0.2
expect_usage_error energy-nan-mu "--mu: key 'analysis.energy.mu[0]' = 'nan'" rimless analysis energy --mu nan
expect_usage_error friction-bad-from "--from: key 'analysis.friction.mu_from' = '-1'" rimless analysis gait-vs-friction --from -1
expect_usage_error friction-inf-to "--to: 'inf' is not a finite number" rimless analysis gait-vs-friction --to inf
expect_usage_error stagnation-bad-to "--to: key 'stagnation.omega_to'" rimless analysis stagnation --to -500 --count 3
expect_usage_error energy-resume "--resume: not used by analysis energy" rimless analysis energy --resume
expect_usage_error energy-count "--count: not used by analysis energy" rimless analysis energy --count 3
expect_usage_error robustness-from "--from: not used by analysis robustness" rimless analysis robustness --from 0.1
expect_usage_error stagnation-mu "--mu: not used by analysis stagnation" rimless analysis stagnation --mu 0.3
expect_usage_error energy-section "--section: not used by analysis energy (only gait-vs-friction, fixed-points, orbit-diagram and basin take it)" rimless analysis energy --section upright
expect_usage_error unknown-analysis "name: fly not in" rimless analysis fly
# The analyses' parameters are keys (analysis.*): a list of reals, each value checked.
expect_usage_error mu-list-item "--set: key 'analysis.robustness.mu[1]' = 'x': not a number" rimless analysis robustness --set "analysis.robustness.mu=[0.6,x]"
expect_usage_error mu-list-scalar "key 'analysis.energy.mu' = '0.6': not a list in brackets" rimless analysis energy --set analysis.energy.mu=0.6
expect_usage_error epsilon-order "key 'analysis.robustness.epsilon_max'" rimless analysis robustness --set analysis.robustness.epsilon_max=1e-4
expect_usage_error orbit-transient "--transient: key 'analysis.orbit.transient' = '0'" rimless analysis orbit-diagram --param rimless.slope --from 0.1 --to 0.2 --count 3 --transient 0
expect_usage_error basin-tolerance "--tolerance: key 'analysis.basin.tolerance' = 'nan'" rimless analysis basin --x initial.omega --y initial.beta --x-range 1:2:2 --y-range -0.1:0.1:2 --tolerance nan
expect_usage_error friction-count "--set: key 'analysis.friction.count' = '0'" rimless analysis gait-vs-friction --set analysis.friction.count=0
"$exe" rimless analysis fixed-points --set 'analysis.fixed_points.mu=[0.2, 0.6]' --out "$work/fp2" --no-plot >/dev/null 2>&1
check "fixed-points with a 2-point mu list: 2 rows at 0.2 and 0.6" test "$(cut -d, -f1 "$work/fp2/fixed_points.csv" | tr '\n' ' ')" = "mu 0.2 0.6 "
check "config.yaml holds the list" grep -q "mu: \[0.2, 0.6\]" "$work/fp2/config.yaml"
"$exe" rimless analysis fixed-points --mu 0.2,0.6 --out "$work/fp2mu" --no-plot >/dev/null 2>&1
check "--mu sets the same key: same bytes" cmp -s "$work/fp2/fixed_points.csv" "$work/fp2mu/fixed_points.csv"
expect_usage_error sweep-inf-to "--to: 'inf' is not a finite number" rimless sweep --param rimless.mu --from 0.2 --to inf --count 3
expect_usage_error sweep-bad-from "--from: key 'rimless.mu' = '-0.2'" rimless sweep --param rimless.mu --from -0.2 --to 0.3 --count 3
expect_usage_error walk-total-mass "key 'robot.total_mass' = '42.53': out of range" humanoid walk --set robot.total_mass=42.53
# Bad robot files: exit 2 naming robot.description and what is wrong (never an internal error, never a
# number MuJoCo would replace or pass on silently).
biped_yaml="$src/tests/humanoid/data/small_biped.yaml"
biped_xml="$src/tests/humanoid/data/small_biped.xml"
bad_robot() {  # bad_robot NAME NEEDLE FILE
  expect_usage_error "$1" "$2" humanoid walk --config "$biped_yaml" --set "robot.description=$3"
}
sed '0,/mass="8"/s//mass="inf"/' "$biped_xml" >"$work/inf_mass.xml"
bad_robot robot-inf-mass "inf_mass.xml': line 13: <geom mass=\"inf\">: 'inf' is not a finite number" "$work/inf_mass.xml"
sed '0,/mass="8"/s//mass="nan"/' "$biped_xml" >"$work/nan_mass.xml"
bad_robot robot-nan-mass "nan_mass.xml': line 13: <geom mass=\"nan\">" "$work/nan_mass.xml"
sed '0,/axis="0 0 1"/s//axis="0 NaN 1"/' "$biped_xml" >"$work/nan_axis.xml"
bad_robot robot-nan-axis "line 15: <joint axis=\"0 NaN 1\">: 'NaN' is not a finite number" "$work/nan_axis.xml"
sed 's/name="LShank" pos="0 0 -0.25"/name="LShank" pos="0 0 nan"/' "$biped_xml" >"$work/nan_pos.xml"
bad_robot robot-nan-pos "key 'robot.description' = '$work/nan_pos.xml': line 27: <body pos=\"0 0 nan\">" "$work/nan_pos.xml"
sed '0,/pos="0 0 0.7"/s//pos="0 0 1e999"/' "$biped_xml" >"$work/overflow.xml"
bad_robot robot-overflow "'1e999' is not a finite number" "$work/overflow.xml"
: >"$work/empty.xml"
bad_robot robot-empty "key 'robot.description' = '$work/empty.xml': the file is empty" "$work/empty.xml"
echo "just text" >"$work/text.urdf"
bad_robot robot-no-element "text.urdf': not an MJCF or URDF file" "$work/text.urdf"
mkfifo "$work/fifo.xml"
bad_robot robot-fifo "fifo.xml': not a regular file" "$work/fifo.xml"
{ echo '<mujoco><!--'; head -c 17000000 /dev/zero | tr '\0' ' '; echo '--></mujoco>'; } >"$work/huge.xml"
bad_robot robot-huge "huge.xml': larger than 16777216 bytes" "$work/huge.xml"
rm -f "$work/huge.xml"
# (MuJoCo's URDF reader takes a negative mass as 0 without a word)
cat >"$work/negative.urdf" <<'URDF'
<robot name="negative">
  <link name="base"><inertial><mass value="2"/><inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <link name="shin"><inertial><mass value="-1"/><inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <joint name="shin_fixed" type="fixed"><parent link="base"/><child link="shin"/></joint>
</robot>
URDF
bad_robot robot-negative-urdf-mass "negative.urdf': line 3: <mass value=\"-1\">: a mass must be >= 0 kg" "$work/negative.urdf"
# The leg as the file has it (joints by role): a role on the wrong leg, a robot that cannot stand.
expect_usage_error robot-role-on-wrong-leg "key 'robot.joints.r_knee' = 'LKnee': this joint is on the leg to LFoot" \
  humanoid walk --config "$biped_yaml" --set robot.joints.l_knee=RKnee --set robot.joints.r_knee=LKnee
expect_usage_error robot-two-roles-one-joint "key 'robot.joints.l_hip_pitch' = 'LHipRoll': also mapped to robot.joints.l_hip_roll" \
  humanoid walk --config "$biped_yaml" --set robot.joints.l_hip_pitch=LHipRoll
sed '0,/name="LHipRoll" axis="1 0 0"/s//name="LHipRoll" axis="0 1 0"/' "$biped_xml" >"$work/parallel_hips.xml"
bad_robot robot-leg-not-6-dof "key 'robot.joints.l_hip_roll' = 'LHipRoll': the left leg's joint axes cannot place the foot in 6 degrees of freedom" \
  "$work/parallel_hips.xml"
expect_usage_error robot-foot-without-sole "key 'robot.feet.left.sole_size' = 'none': the foot LFoot has no contact geom" \
  humanoid walk --config "$biped_yaml" --set robot.feet.left.sole_geom=none
sed 's/range="-2.4 0"/range="-0.1 0"/' "$src/tests/humanoid/data/minus_y_knee.xml" >"$work/stiff_knee.xml"
expect_usage_error robot-no-standing-pose "key 'robot.joints.r_knee': standing at walk.pelvis_height = 0.6" \
  humanoid walk --config "$src/tests/humanoid/data/minus_y_knee.yaml" --set "robot.description=$work/stiff_knee.xml"
# Export and load back with the configuration written beside the file (no --set): a robot with -y
# knees walks with the same summary as from its own file (MJCF: the same numbers; URDF: the same
# robot re-anchored on its joints, to 1e-9 relative).
knee_yaml="$src/tests/humanoid/data/minus_y_knee.yaml"
"$exe" humanoid walk --config "$knee_yaml" --set walk.steps=2 --no-plot --out "$work/knee0" >/dev/null 2>&1
for fmt in mjcf urdf; do
  "$exe" humanoid export --config "$knee_yaml" --format "$fmt" --out "$work/knee_$fmt.$([ $fmt = mjcf ] && echo xml || echo urdf)" >"$work/out" 2>&1
  check "export $fmt: the configuration beside it is named" grep -qF "load it back with --config $work/knee_$fmt.yaml" "$work/out"
  "$exe" humanoid walk --config "$work/knee_$fmt.yaml" --set walk.steps=2 --no-plot --out "$work/knee_$fmt" >/dev/null 2>&1
  check "export $fmt, loaded back with --config alone: walks (exit $?)" test -f "$work/knee_$fmt/summary.json"
  check "export $fmt, loaded back: the original's summary" /usr/bin/python3 -c "
import json, sys
a, b = (json.load(open(sys.argv[i] + '/summary.json')) for i in (1, 2))
skip = {'wall_time', 'real_time_factor'}
for k, v in a.items():
    if k in skip or isinstance(v, bool) or not isinstance(v, (int, float)):
        assert k in skip or a[k] == b[k], k
    else:
        assert abs(v - b[k]) <= 1e-9 * max(1.0, abs(v)), (k, v, b[k])" "$work/knee0" "$work/knee_$fmt"
done
expect_usage_error mismatch-nan-scale "--scales: 'nan' is not a finite number" humanoid mismatch --scales nan
expect_usage_error mismatch-empty-scale "--scales: '' is not a finite number" humanoid mismatch --scales 0.9,,1.1
expect_usage_error walk-nan-fps "--fps: 'nan' is not a finite number" humanoid walk --render --fps nan
echo "not a directory" >"$work/afile"
for cmd in "rimless simulate" "rimless fixed-point" "humanoid bench"; do
  # shellcheck disable=SC2086
  timeout 60 "$exe" $cmd --out "$work/afile" --no-plot >/dev/null 2>"$work/err"
  code=$?
  check "$cmd: a file as --out is exit 2 before computing (got $code)" test "$code" -eq 2
  check "$cmd: names --out: $(cat "$work/err")" grep -q -- "--out: cannot make the run directory" "$work/err"
done
expect_usage_error no-subcommand "flexgait rimless --help" rimless
"$exe" rimless simulate --steps 3 --omega0 1.4 --out "$work/run1" --no-plot --json >"$work/summary.out" 2>"$work/err"
rc=$?  # (before $(cat) in the message resets $?)
check "simulate exits 0: $(cat "$work/err")" test "$rc" -eq 0
for f in config.yaml log.csv events.csv steps.csv summary.json; do check "run writes $f" test -s "$work/run1/$f"; done
check "--json prints the summary" cmp -s "$work/summary.out" "$work/run1/summary.json"
for key in steps gaits mean_speed energy_initial energy_final work_damping work_friction energy_balance_error failure; do
  check "summary has $key" grep -q "\"$key\"" "$work/run1/summary.json"
done
check "no temporary files left" test -z "$(find "$work/run1" -name '.*tmp*')"
"$exe" rimless simulate --config "$work/run1/config.yaml" --out "$work/run2" --no-plot >/dev/null 2>&1
check "config.yaml of a run reproduces it" cmp -s "$work/run1/log.csv" "$work/run2/log.csv"
"$exe" rimless simulate --steps 3 --out "$work/run3" --no-plot >/dev/null 2>&1
check "identical bytes on a rerun" cmp -s "$work/run1/events.csv" "$work/run3/events.csv"
"$exe" rimless simulate --model rigid --steps 3 --out "$work/rigid" --no-plot --json >"$work/rigid.json" 2>&1
check "rigid model runs" grep -q '"model": "rigid"' "$work/rigid.json"
if /usr/bin/python3 -c "import matplotlib" 2>/dev/null; then
  FLEXGAIT_PLOT_DIR="$src/python" "$exe" rimless simulate --steps 3 --out "$work/plot" >/dev/null 2>&1
  check "plot written as PNG" sh -c "head -c 8 '$work/plot/rimless.png' | grep -q PNG"
fi
# Fixed points and sweeps.
"$exe" rimless fixed-point --out "$work/fp" --json --no-plot >"$work/fp.json" 2>"$work/err"
rc=$?
check "fixed-point exits 0: $(cat "$work/err")" test "$rc" -eq 0
for key in converged iterations residual state multipliers stable gait; do
  check "fixed-point JSON has $key" grep -q "\"$key\"" "$work/fp.json"
done
check "fixed point converged" grep -q '"converged": true' "$work/fp.json"
"$exe" rimless fixed-point --model rigid --section upright --out "$work/fpr" --json --no-plot >"$work/fpr.json" 2>&1
check "rigid fixed point converged" grep -q '"converged": true' "$work/fpr.json"
# A failed search is a named failure (exit 1, one line on stderr), its report without numbers of no
# meaning: no starting point for Newton, a Jacobian column that failed.
"$exe" rimless fixed-point --set initial.omega=-1 --out "$work/fp_none" --json --no-plot >"$work/fp_none.json" 2>"$work/err"
check "fixed point without a start exits 1 (got $?)" test $? -eq 1
check "fixed point without a start: one line naming the failure: $(cat "$work/err")" \
  sh -c "test \$(wc -l <'$work/err') -eq 1 && grep -q 'no fixed point.*no initial guess' '$work/err'"
check "fixed point without a start: state null" grep -q '"state": null' "$work/fp_none/fixed_point.json"
"$exe" rimless fixed-point --set rimless.mu_s=0.1559 --set rimless.mu_k=0.1559 --set initial.omega=1.5 \
  --set analysis.transient_steps=60 --out "$work/fp_fd" --json --no-plot >"$work/fp_fd.json" 2>"$work/err"
code=$?
if grep -q '"converged": false' "$work/fp_fd.json"; then
  check "failed fixed point exits 1 (got $code)" test "$code" -eq 1
  check "failed fixed point: multipliers null" grep -q '"multipliers": null' "$work/fp_fd.json"
  check "failed fixed point: no number of uninitialised memory" sh -c "! grep -Eq 'e[+-][0-9]{3}' '$work/fp_fd.json'"
else
  check "converged fixed point exits 0 (got $code)" test "$code" -eq 0
fi
expect_usage_error sweep-bad-param "rimless.nope" rimless sweep --param rimless.nope --from 0 --to 1 --count 3
expect_usage_error sweep-bad-value "rimless.K" rimless sweep --param rimless.K --from -1 --to 1 --count 3
"$exe" rimless sweep --param rimless.mu --from 0.2 --to 0.6 --count 6 --jobs 2 --out "$work/sweep_full" --no-plot >/dev/null 2>&1
check "sweep writes sweep.csv with 6 points" test "$(wc -l <"$work/sweep_full/sweep.csv")" -eq 7
# Kill a sweep part-way, resume it, and compare with the one run through.
"$exe" rimless sweep --param rimless.mu --from 0.2 --to 0.6 --count 6 --jobs 1 --out "$work/sweep_killed" --no-plot >/dev/null 2>&1 &
pid=$!
for _ in $(seq 1 200); do
  [ -s "$work/sweep_killed/sweep.partial.csv" ] && break
  sleep 0.01
done
kill -9 "$pid" 2>/dev/null
wait "$pid" 2>/dev/null
"$exe" rimless sweep --param rimless.mu --from 0.2 --to 0.6 --count 6 --jobs 2 --resume --out "$work/sweep_killed" --no-plot >/dev/null 2>&1
check "killed and resumed sweep equals the one run through" cmp -s "$work/sweep_full/sweep.csv" "$work/sweep_killed/sweep.csv"
check "a finished sweep's directory is marked complete" test -f "$work/sweep_full/complete"
check "the resumed sweep's directory is marked complete" test -f "$work/sweep_killed/complete"
# A partial file whose rows have the right number of fields but one damaged cell each (another
# point's value, text for a number, a non-boolean, a fractional count, a broken state list, a
# converged point with a failure): every row is computed again, to the same bytes.
cp -r "$work/sweep_full" "$work/sweep_damaged"
python3 - "$work/sweep_full/sweep.csv" "$work/sweep_damaged/sweep.partial.csv" <<'PY'
import csv, sys
rows = list(csv.reader(open(sys.argv[1])))[1:]
header = next(csv.reader(open(sys.argv[1])))
damage = [("value", "0.3"), ("transient_speed", "fast"), ("converged", "maybe"), ("iterations", "2.5"),
          ("state", "1;x"), ("failure", "fell over")]
for row, (column, text) in zip(rows, damage):
    row[header.index(column)] = text
    if column == "failure":
        row[header.index("converged")] = "true"
with open(sys.argv[2], "w", newline="") as f:
    csv.writer(f, lineterminator="\n").writerows(rows)
PY
"$exe" rimless sweep --param rimless.mu --from 0.2 --to 0.6 --count 6 --resume --out "$work/sweep_damaged" \
  --no-plot >"$work/out" 2>&1
check "resume computes every damaged row again: $(cat "$work/out")" grep -q "6 computed, 0 resumed" "$work/out"
check "resume from damaged rows equals the one run through" cmp -s "$work/sweep_full/sweep.csv" "$work/sweep_damaged/sweep.csv"
cp "$work/sweep_full/sweep.csv" "$work/sweep_damaged/sweep.partial.csv"
sed -i 1d "$work/sweep_damaged/sweep.partial.csv"
"$exe" rimless sweep --param rimless.mu --from 0.2 --to 0.6 --count 6 --resume --out "$work/sweep_damaged" \
  --no-plot >"$work/out" 2>&1
check "resume keeps every sound row: $(cat "$work/out")" grep -q "0 computed, 6 resumed" "$work/out"
expect_usage_error resume-other-sweep "--resume" rimless sweep --param rimless.mu --from 0.3 --to 0.6 --count 6 --resume
for name in fixed-points energy; do
  "$exe" rimless analysis "$name" --out "$work/an_$name" --no-plot >/dev/null 2>"$work/err"
  rc=$?
  check "analysis $name exits 0: $(cat "$work/err")" test "$rc" -eq 0
done
# Stagnation: a small scan (4 grid points bracketing omega_c, offsets 1e-1 .. 1e-3 on both sides).
stag=(rimless analysis stagnation --config "$src/configs/rimless-stagnation.yaml" --count 4 --from 0.5 --to 0.56
      --set stagnation.offset_min=1e-3 --set stagnation.per_decade=1 --no-plot)
"$exe" "${stag[@]}" --out "$work/an_stag" >/dev/null 2>"$work/err"
rc=$?
check "analysis stagnation exits 0: $(cat "$work/err")" test "$rc" -eq 0
check "stagnation writes 4 grid points and 6 scan points" test "$(wc -l <"$work/an_stag/stagnation.csv")" -eq 11
check "stagnation finds omega_c" grep -q '"omega_c": 0.53038867' "$work/an_stag/stagnation.json"
"$exe" "${stag[@]}" --out "$work/an_stag2" >/dev/null 2>&1
check "stagnation: same bytes twice" cmp -s "$work/an_stag/stagnation.csv" "$work/an_stag2/stagnation.csv"
check "stagnation summary: same bytes twice" cmp -s "$work/an_stag/stagnation.json" "$work/an_stag2/stagnation.json"
map=(rimless analysis stagnation-map --config "$src/configs/rimless-stagnation.yaml" --count 3 --from 0.4 --to 0.6
     --set stagnation.offset_min=1e-2 --vary rimless.C=20 --vary rimless.K=2000,rimless.C=40 --no-plot)
"$exe" "${map[@]}" --jobs 1 --out "$work/an_map1" >/dev/null 2>"$work/err"
rc=$?
check "stagnation-map exits 0: $(cat "$work/err")" test "$rc" -eq 0
"$exe" "${map[@]}" --jobs 2 --out "$work/an_map2" >/dev/null 2>&1
check "stagnation-map: same bytes with 1 and 2 jobs" cmp -s "$work/an_map1/stagnation_map.csv" "$work/an_map2/stagnation_map.csv"
expect_usage_error stagnation-start-past-vertical initial.beta rimless analysis stagnation --set initial.beta=0
expect_usage_error stagnation-window stagnation.window rimless analysis stagnation \
  --config "$src/configs/rimless-stagnation.yaml" --set stagnation.window=-1
expect_usage_error stagnation-offsets stagnation.offset_min rimless analysis stagnation \
  --config "$src/configs/rimless-stagnation.yaml" --set stagnation.offset_min=0.5
expect_usage_error stagnation-map-key rimless.Q rimless analysis stagnation-map \
  --config "$src/configs/rimless-stagnation.yaml" --vary rimless.Q=3
expect_usage_error stagnation-map-value rimless.I rimless analysis stagnation-map \
  --config "$src/configs/rimless-stagnation.yaml" --vary rimless.I=-1

# Continuation of the gait: the rigid wheel over the slope, same bytes twice; bad input.
cont=(rimless continuation --model rigid --param rimless.slope --from 0.05 --to 0.15 --no-plot)
"$exe" "${cont[@]}" --out "$work/cont1" >/dev/null 2>"$work/err"
rc=$?
check "continuation exits 0: $(cat "$work/err")" test "$rc" -eq 0
check "continuation: branch.csv columns" test "$(head -1 "$work/cont1/branch.csv")" = \
  "parameter,thetad,mode,period,speed,dissipated_per_step,gait,abs_lambda_1,arg_lambda_1,stable,residual,event,key,section,computed_at"
check "continuation: every row says its key, section and wheel" python3 -c "
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
assert rows and all(r['key'] == 'rimless.slope' and r['section'] == 'touchdown' for r in rows), rows[0]
assert len({r['computed_at'] for r in rows}) == 1 and 'sim.model=rigid' in rows[0]['computed_at'], rows[0]
assert 'rimless.slope=' not in rows[0]['computed_at'], rows[0]
" "$work/cont1/branch.csv"
# Started on a key's bound (rimless.I >= 0) and continued to it: the difference step stays inside.
for ends in "0 0.05" "0.05 0"; do
  read -r lo hi <<<"$ends"
  "$exe" rimless continuation --model rigid --param rimless.I --from "$lo" --to "$hi" --no-plot \
    --out "$work/cont-bound-$lo" >"$work/out" 2>"$work/err"
  rc=$?
  check "continuation from $lo to $hi (a bound) exits 0 (got $rc): $(cat "$work/err")" test "$rc" -eq 0
  check "continuation from $lo to $hi reaches its end" grep -q "reached rimless.I = $hi" "$work/out"
done
check "continuation reaches the end" grep -q "^0.15," "$work/cont1/branch.csv"
"$exe" "${cont[@]}" --out "$work/cont2" >/dev/null 2>&1
check "continuation: same bytes twice" cmp -s "$work/cont1/branch.csv" "$work/cont2/branch.csv"
expect_usage_error continuation-key rimless.nothing rimless continuation --param rimless.nothing --from 0.05 --to 0.1
expect_usage_error continuation-solver-key 'a branch follows a parameter of the wheel' rimless continuation --param solver.rtol --from 1e-10 --to 1e-3
expect_usage_error continuation-empty-interval "--to" rimless continuation --param rimless.slope --from 0.1 --to 0.1

# Humanoid stiffness bench.
"$exe" humanoid bench --out "$work/bench" --json --no-plot >"$work/bench.json" 2>"$work/err"
rc=$?
check "humanoid bench exits 0: $(cat "$work/err")" test "$rc" -eq 0
for key in k_fit r_squared max_error_uncompensated max_error_compensated; do
  check "bench summary has $key" grep -q "\"$key\"" "$work/bench.json"
done
expect_usage_error bench-bad-k "plant.k_joint" humanoid bench --set plant.k_joint=0

# Humanoid walk.
"$exe" humanoid walk --config "$src/configs/walk-robotis.yaml" --set walk.steps=2 --out "$work/walk" --json \
  --no-plot >"$work/walk.json" 2>"$work/err"
rc=$?
check "humanoid walk exits 0: $(cat "$work/err")" test "$rc" -eq 0
for key in fell steps_completed zmp_rms_x zmp_rms_y pelvis_roll_error_max pelvis_pitch_error_max \
           pelvis_roll_error_rms landing_error_max com_error_rms; do
  check "walk summary has $key" grep -q "\"$key\"" "$work/walk.json"
done
check "walk did not fall" grep -q '"fell": false' "$work/walk.json"
check "walk's outcome is walked" grep -q '"outcome": "walked"' "$work/walk.json"
# A push that throws the robot off the floor is no success: outcome airborne, exit 1, one line.
"$exe" humanoid walk --set walk.steps=3 --set disturbance.push.time=1 --set disturbance.push.force_z=5000 \
  --set disturbance.push.duration=0.5 --out "$work/thrown" --json --no-plot >"$work/thrown.json" 2>"$work/err"
rc=$?
check "a thrown robot exits 1 (got $rc)" test "$rc" -eq 1
check "a thrown robot is airborne: $(cat "$work/err")" grep -q '"outcome": "airborne"' "$work/thrown.json"
check "a thrown robot's error names the outcome" grep -q "^error: .*outcome airborne" "$work/err"
for f in log.csv footsteps.csv summary.json config.yaml; do check "walk writes $f" test -s "$work/walk/$f"; done
"$exe" humanoid walk --config "$src/configs/walk-rough.yaml" --set terrain.rough.seed=2 --out "$work/rough" --no-plot \
  >/dev/null 2>"$work/err"
rc=$?
check "walk-rough.yaml walks 10 steps on the 1 cm floor of seed 2: $(cat "$work/err")" test "$rc" -eq 0
expect_usage_error continuation-zero-step "--step: '0' is not greater than 0" rimless continuation \
  --param rimless.slope --from 0.1 --to 0.11 --step 0
expect_usage_error continuation-nan-step "--step: 'nan' is not a finite number" rimless continuation \
  --param rimless.slope --from 0.1 --to 0.11 --step nan
expect_usage_error walk-bad-step-time "walk.step_time" humanoid walk --set walk.step_time=0
expect_usage_error walk-typo "walk.steps" humanoid walk --set walk.stepz=3
for f in joints.csv timing.json; do check "walk writes $f" test -s "$work/walk/$f"; done
for key in compensation estimate_error_rms newton_iterations_max newton_failures deflection_rms; do
  check "walk summary has $key" grep -q "\"$key\"" "$work/walk.json"
done
check "walk compensates by default" grep -q '"compensation": "both"' "$work/walk.json"
expect_usage_error walk-bad-compensation "control.compensation" humanoid walk --set control.compensation=sometimes
expect_usage_error walk-bad-gravity-model "control.gravity_model" humanoid walk --set control.gravity_model=rigid
expect_usage_error walk-bad-k-belief "control.k_joint" humanoid walk --set control.k_joint=0
expect_usage_error walk-push-unknown-body "key 'disturbance.push.body' = 'arm'" humanoid walk --set disturbance.push.body=arm
expect_usage_error walk-push-in-the-past "key 'disturbance.push.time' = '-1'" humanoid walk --set disturbance.push.time=-1
expect_usage_error walk-push-negative-duration "key 'disturbance.push.duration' = '-0.1'" humanoid walk --set disturbance.push.duration=-0.1
expect_usage_error walk-terrain-unknown-kind "key 'terrain.kind' = 'hill'" humanoid walk --set terrain.kind=hill
expect_usage_error walk-terrain-steep-ramp "key 'terrain.ramp.angle' = '0.5'" humanoid walk --set terrain.kind=ramp --set terrain.ramp.angle=0.5
expect_usage_error walk-terrain-step-beyond-reach "key 'terrain.step.height' = '-0.09'" humanoid walk --set terrain.kind=step \
  --set terrain.step.height=-0.09
expect_usage_error walk-terrain-flat-rough "key 'terrain.rough.amplitude' = '0'" humanoid walk --set terrain.kind=rough \
  --set terrain.rough.amplitude=0
# Walking height and step width: the robot's own unless set (auto), checked against its legs and soles.
expect_usage_error walk-pelvis-beyond-reach "key 'walk.pelvis_height' = '0.8'" humanoid walk --set walk.pelvis_height=0.8
expect_usage_error walk-soles-overlap "key 'walk.step_width' = '0.1'" humanoid walk --set walk.step_width=0.1
expect_usage_error compensated-feedback-needs-output "key 'control.compensated_feedback' = 'true' needs the output" humanoid walk --set control.compensated_feedback=true --set control.compensation=input
expect_usage_error horizontal-force-needs-dynamic "key 'control.plan_horizontal_force' = '0.5' needs the plan's motion" humanoid walk --set control.plan_horizontal_force=0.5 --set control.load_model=measured
expect_usage_error horizontal-force-bounds "control.plan_horizontal_force" humanoid walk --set control.plan_horizontal_force=1.5 --set control.load_model=dynamic
expect_usage_error gyro-rest-longer-than-the-still-stance "key 'control.k_estimation_gyro_rest' = '1' is longer than the still start stance" humanoid walk --set control.k_estimation_gyro_rest=1
expect_usage_error calibrate-needs-the-calibration "key 'control.k_estimation' = 'calibrate' needs the calibration in the start stance" humanoid walk --set control.k_estimation=calibrate --set control.load_model=measured
expect_usage_error calibrate-needs-measured-loads "key 'control.k_estimation' = 'calibrate' needs each foot's measured load" humanoid walk --set control.load_model=gravity --set control.k_estimation=calibrate --set calibration.time=10 --set walk.start_time=14
expect_usage_error calibration-longer-than-the-start-stance "key 'calibration.time' = '10' does not end before the COM moves" humanoid walk --set calibration.time=10
expect_usage_error walk-height-not-auto "key 'walk.steps'" humanoid walk --set walk.steps=auto
check "builtin walk height is written derived" grep -q "pelvis_height: 0.723" "$work/walk/config.yaml"
"$exe" humanoid walk --config "$src/tests/humanoid/data/small_biped.yaml" --set walk.pelvis_height=auto \
  --set walk.step_width=auto --set walk.steps=0 --set walk.start_time=0.1 --set walk.end_time=0 --out "$work/biped" \
  --no-plot >/dev/null 2>"$work/err"
rc=$?
check "second robot stands at its own height: $(cat "$work/err")" test "$rc" -eq 0
check "second robot's derived height in config.yaml" grep -q "pelvis_height: 0.57 " "$work/biped/config.yaml"
check "second robot's derived step width in config.yaml" grep -q "step_width: 0.15 " "$work/biped/config.yaml"

# Humanoid compensation study and stiffness mismatch (one short step each).
"$exe" humanoid compensation --config "$src/configs/walk-robotis.yaml" --set walk.steps=1 --out "$work/comp" \
  --json --no-plot >"$work/comp.json" 2>"$work/err"
rc=$?
check "humanoid compensation exits 0: $(cat "$work/err")" test "$rc" -eq 0
for d in off both both-thesis-form; do check "compensation writes $d/summary.json" test -s "$work/comp/$d/summary.json"; done
for key in pelvis_roll_error_max_off pelvis_roll_error_max_on pelvis_roll_error_max_cut estimate_error_share_of_deflection \
           newton_conventional_max; do
  check "comparison has $key" grep -q "\"$key\"" "$work/comp/comparison.json"
done
"$exe" humanoid mismatch --config "$src/configs/walk-robotis.yaml" --set walk.steps=1 --scales 0.9,1.1 \
  --out "$work/mismatch" --no-plot >"$work/out" 2>"$work/err"
rc=$?
check "humanoid mismatch exits 0: $(cat "$work/err")" test "$rc" -eq 0
check "mismatch has two rows" test "$(grep -c k_joint_true "$work/mismatch/comparison.json")" -eq 2
for d in k090-off k090-both k110-off k110-both; do check "mismatch writes $d" test -s "$work/mismatch/$d/summary.json"; done
expect_usage_error mismatch-bad-scale "scales" humanoid mismatch --scales 0
"$exe" reproduce --help >"$work/help3" 2>&1
check "reproduce --help mentions index.html" grep -q "index.html" "$work/help3"

# Outcomes decide the exit code: an early stop or a failed
# simulation is exit 1 with the reason; MuJoCo's messages go to stderr (stdout stays JSON) and
# no MUJOCO_LOG.TXT appears; an infeasible start names its keys (exit 2).
expect_usage_error many-legs-sag "rimless.legs = 50" rimless simulate --set rimless.legs=50
expect_usage_error soft-legs "rimless.K = 1e-06" rimless simulate --set rimless.K=1e-6
(cd "$work" && timeout 120 "$exe" rimless simulate --set rimless.legs=3 --no-plot --out "$work/legs3" >/dev/null 2>"$work/err")
check "a wheel that stops early exits 1 (got $?)" test $? -eq 1
check "the early stop is named on stderr" grep -q "error: stopped after" "$work/err"
(cd "$work" && timeout 120 "$exe" humanoid walk --set walk.steps=2 --set plant.k_joint=1e308 --json --no-plot \
  --out "$work/unstable" >"$work/unstable.json" 2>"$work/err")
check "an unstable walk exits 1 (got $?)" test $? -eq 1
check "its stdout is JSON naming the failure" python3 -c "import json,sys; d=json.load(open(sys.argv[1])); assert d['failure'].startswith('MuJoCo:'), d" "$work/unstable.json"
check "MuJoCo's warnings on stderr" grep -q "warning: MuJoCo:" "$work/err"
(cd "$work" && timeout 120 "$exe" humanoid bench --set plant.k_joint=1e308 --no-plot --out "$work/bench-unstable" \
  >/dev/null 2>"$work/err")
check "an unstable bench exits 1 (got $?)" test $? -eq 1
check "the bench failure is named" grep -q "error: the stiffness bench failed" "$work/err"
check "no MUJOCO_LOG.TXT" test ! -e "$work/MUJOCO_LOG.TXT"
timeout 60 "$exe" rimless simulate --set rimless.K=1e9 --set sim.max_wall_time=1 --set sim.max_step_rate=1e12 --no-plot --out "$work/stiff" \
  >/dev/null 2>"$work/err"
check "a stiff run that makes no progress ends at sim.max_wall_time, exit 1 (got $?)" test $? -eq 1
check "it names the limit and suggests bdf" grep -q "sim.max_wall_time reached.*solver.method=bdf" "$work/err"
# The deterministic work limit: a stiff leg (K = 1e9 N/m) holds dop853 at ~5e6 steps per simulated
# second and ends at once; a damper that makes |lambda| = 1e9 1/s is refused before the first step.
timeout 60 "$exe" rimless simulate --set rimless.K=1e9 --no-plot --out "$work/stiff1" >/dev/null 2>"$work/err"
check "a stiff leg ends at sim.max_step_rate, exit 1 (got $?)" test $? -eq 1
check "it names the work limit, the leg's mode and bdf: $(cat "$work/err")" \
  grep -q "sim.max_step_rate reached.*lambda.*solver.method=bdf" "$work/err"
timeout 60 "$exe" rimless simulate --set rimless.C=1e9 --no-plot --out "$work/stiff2" >/dev/null 2>"$work/err"
check "a stiff damper ends before its first step, exit 1 (got $?)" test $? -eq 1
check "it names the work limit and bdf: $(cat "$work/err")" \
  grep -q "sim.max_step_rate exceeded from the start.*stability.*solver.method=bdf" "$work/err"
timeout 60 "$exe" rimless simulate --set rimless.C=1e9 --set solver.method=bdf --no-plot --out "$work/stiff3" >/dev/null 2>"$work/err"
rc=$?
check "with bdf the same stiff damper walks its 20 steps: $(cat "$work/err")" test "$rc" -eq 0
check "a run that ended for a reason is still complete (its files are written)" test -f "$work/stiff2/complete"

# The complete marker: a run killed mid-way has none (and its temporaries are removed when the
# directory is written again); a finished run has one; a usage error writes nothing at all.
# (a run of 1e6 s: its log's projected 4e11 bytes need sim.max_log_bytes lifted)
"$exe" rimless simulate --set sim.steps=200000 --set sim.max_time=1e6 --set sim.max_log_bytes=1e15 --no-plot \
  --out "$work/killed" >/dev/null 2>&1 &
pid=$!
for _ in $(seq 1 3000); do
  ls -a "$work/killed" 2>/dev/null | grep -q '^\.log\.csv\.tmp-' && break
  sleep 0.01
done
sleep 0.2
kill -9 "$pid" 2>/dev/null
wait "$pid" 2>/dev/null
check "a killed run has no complete marker" test ! -e "$work/killed/complete"
check "a killed run leaves its temporaries" test -n "$(ls -a "$work/killed" | grep '^\.log\.csv\.tmp-')"
"$exe" rimless simulate --set sim.steps=2 --no-plot --out "$work/killed" >/dev/null 2>&1
check "the run written again over it is complete" test -f "$work/killed/complete"
check "and the killed writer's temporaries are gone: $(ls -a "$work/killed" | tr '\n' ' ')" \
  test -z "$(ls -a "$work/killed" | grep '\.tmp-')"

# ---- orbit diagram and basin ----
# The rigid wheel's orbit diagram over the slope: every recorded crossing is ω*(φ) (closed form
# r sqrt(a/(1 - r²)), rigid_wheel.hpp) to 1e-8 rad/s; the same bytes for 1 and 2 threads.
orbit=(rimless analysis orbit-diagram --set sim.model=rigid --param rimless.slope --from 0.05 --to 0.2 --count 4
       --transient 60 --record 5 --no-plot)
timeout 120 "$exe" "${orbit[@]}" --jobs 1 --out "$work/orbit1" >/dev/null 2>"$work/err"
rc=$?
check "orbit-diagram exits 0: $(cat "$work/err")" test "$rc" -eq 0
timeout 120 "$exe" "${orbit[@]}" --jobs 2 --out "$work/orbit2" >/dev/null 2>&1
check "orbit-diagram: same bytes for 1 and 2 threads" cmp -s "$work/orbit1/orbit.csv" "$work/orbit2/orbit.csv"
check "orbit-diagram: orbit.csv columns" test "$(head -1 "$work/orbit1/orbit.csv")" = \
  "parameter,step,mode,gait,thetad,state,failure"
check "orbit-diagram: the rigid wheel sits on omega*(phi)" python3 -c "
import csv, math, sys
m, L0, I, g, N = 1.0, 1.0, 0.3, 9.81, 10
a_ = math.pi / N
for r in csv.DictReader(open(sys.argv[1])):
    phi = float(r['parameter'])
    J = m * L0 * L0 + I
    rr = (m * L0 * L0 * math.cos(2 * a_) + I) / J
    a = 4 * m * g * L0 * math.sin(a_) * math.sin(phi) / J
    assert abs(float(r['thetad']) - rr * math.sqrt(a / (1 - rr * rr))) < 1e-8, r
" "$work/orbit1/orbit.csv"
# --branch: a branch.csv of the same key, section and wheel is drawn; another key, section, model or
# wheel parameter is refused naming --branch and both; a branch.csv without the record (written
# before it) is drawn with a warning.
branch_orbit=(rimless analysis orbit-diagram --set sim.model=rigid --param rimless.slope --from 0.05 --to 0.15
              --count 2 --transient 5 --record 2)
timeout 120 "$exe" "${branch_orbit[@]}" --branch "$work/cont1/branch.csv" --no-plot --out "$work/orbit-branch" \
  >/dev/null 2>"$work/err"
rc=$?
check "orbit-diagram --branch of the same branch exits 0 (got $rc): $(cat "$work/err")" test "$rc" -eq 0
check "orbit-diagram --branch: copied as branch_1.csv" cmp -s "$work/cont1/branch.csv" "$work/orbit-branch/branch_1.csv"
expect_usage_error orbit-branch-key "--branch: '$work/cont1/branch.csv' was continued in rimless.slope, not in the requested --param rimless.L0" \
  "${branch_orbit[@]/rimless.slope/rimless.L0}" --branch "$work/cont1/branch.csv"
expect_usage_error orbit-branch-section "not on the requested --section upright" \
  "${branch_orbit[@]}" --section upright --branch "$work/cont1/branch.csv"
expect_usage_error orbit-branch-model "sim.model = rigid (here: flexible)" \
  "${branch_orbit[@]/sim.model=rigid/sim.model=flexible}" --branch "$work/cont1/branch.csv"
expect_usage_error orbit-branch-wheel "rimless.K = 1000.0 (here: 2000.0)" \
  "${branch_orbit[@]}" --set rimless.K=2000 --branch "$work/cont1/branch.csv"
expect_usage_error orbit-branch-fifo "is not a regular file" "${branch_orbit[@]}" --branch /dev/null
cut -d, -f1-12 "$work/cont1/branch.csv" >"$work/old-branch.csv"
timeout 120 "$exe" "${branch_orbit[@]}" --branch "$work/old-branch.csv" --no-plot --out "$work/orbit-old-branch" \
  >/dev/null 2>"$work/err"
rc=$?
check "orbit-diagram --branch of an old branch.csv exits 0 (got $rc)" test "$rc" -eq 0
check "orbit-diagram --branch of an old branch.csv warns: $(cat "$work/err")" \
  grep -q "^warning: --branch: .* does not say which key" "$work/err"
expect_usage_error orbit-key rimless.nothing rimless analysis orbit-diagram --param rimless.nothing --from 0.1 --to 0.2 --count 3
expect_usage_error orbit-empty "--to" rimless analysis orbit-diagram --param rimless.slope --from 0.1 --to 0.1 --count 3
expect_usage_error orbit-count "--count" rimless analysis orbit-diagram --param rimless.slope --from 0.1 --to 0.2 --count 1
expect_usage_error orbit-basin-option "--x-range" rimless analysis orbit-diagram --param rimless.slope --from 0.1 --to 0.2 --count 3 --x-range 0:1:3
# A small basin of the rigid wheel: one row per cell, the area in summary.json, the same bytes
# for 1 and 2 threads.
basin=(rimless analysis basin --set sim.model=rigid --x initial.omega --y initial.beta --x-range -1:2.5:8
       --y-range -0.25:0.25:5 --no-plot)
timeout 120 "$exe" "${basin[@]}" --jobs 1 --out "$work/basin1" >/dev/null 2>"$work/err"
rc=$?
check "basin exits 0: $(cat "$work/err")" test "$rc" -eq 0
timeout 120 "$exe" "${basin[@]}" --jobs 2 --out "$work/basin2" >/dev/null 2>&1
check "basin: same bytes for 1 and 2 threads" cmp -s "$work/basin1/basin.csv" "$work/basin2/basin.csv"
check "basin: 40 cells" test "$(tail -n +2 "$work/basin1/basin.csv" | wc -l)" -eq 40
check "basin: converged and rolled-back cells, area = converged x cell" python3 -c "
import json, sys
d = json.load(open(sys.argv[1]))
o = d['outcomes']
assert o['converged'] > 0 and o['rolled_back'] > 0, o
assert abs(d['basin_area'] - o['converged'] * 0.5 * 0.125) < 1e-12, d
assert d['reference']['found'] and d['reference']['stable'], d
" "$work/basin1/summary.json"
# --resume from a partial file whose rows have the right number of fields but damaged cells (the
# orbit diagram's reduction used to stop on them as an internal error): computed again, same bytes.
damage_rows() {  # damage_rows FINAL_CSV PARTIAL_CSV COLUMN=TEXT...: row k of FINAL (no header) gets damage k
  python3 - "$@" <<'PY'
import csv, sys
final, partial, damage = sys.argv[1], sys.argv[2], sys.argv[3:]
table = list(csv.reader(open(final)))
header, rows = table[0], table[1:]
for row, item in zip(rows, damage * len(rows)):
    column, text = item.split("=", 1)
    row[header.index(column)] = text
with open(partial, "w", newline="") as f:
    csv.writer(f, lineterminator="\n").writerows(rows)
PY
}
for kind in orbit basin; do
  cp -r "$work/${kind}1" "$work/${kind}_damaged"
done
damage_rows "$work/orbit1/orbit_points.csv" "$work/orbit_damaged/orbit_points.partial.csv" recorded=abc recorded=4 \
  thetad=1 states=x "failure=fell over"
damage_rows "$work/basin1/basin.csv" "$work/basin_damaged/basin.partial.csv" x=9 outcome=flew steps=-1 distance=far
timeout 120 "$exe" "${orbit[@]}" --resume --out "$work/orbit_damaged" >"$work/out" 2>&1
check "orbit-diagram --resume computes damaged rows again: $(cat "$work/out")" grep -q "4 computed, 0 resumed" "$work/out"
check "orbit-diagram --resume from damaged rows: same bytes" cmp -s "$work/orbit1/orbit.csv" "$work/orbit_damaged/orbit.csv"
timeout 120 "$exe" "${basin[@]}" --resume --out "$work/basin_damaged" >"$work/out" 2>&1
check "basin --resume computes damaged rows again: $(tail -2 "$work/out")" grep -q "40 computed, 0 resumed" "$work/out"
check "basin --resume from damaged rows: same bytes" cmp -s "$work/basin1/basin.csv" "$work/basin_damaged/basin.csv"
expect_usage_error basin-key "--x" rimless analysis basin --x rimless.slope --y initial.beta --x-range 0:1:3 --y-range 0:0.1:3
expect_usage_error basin-empty "--x-range" rimless analysis basin --x initial.omega --y initial.beta --x-range 1:1:3 --y-range 0:0.1:3
expect_usage_error basin-count "--y-range" rimless analysis basin --x initial.omega --y initial.beta --x-range 0:1:3 --y-range 0:0.1:1
expect_usage_error basin-beta "initial.beta" rimless analysis basin --x initial.omega --y initial.beta --x-range 0:1:3 --y-range 0:0.5:3
expect_usage_error basin-from "--from" rimless analysis basin --x initial.omega --y initial.beta --x-range 0:1:3 --y-range 0:0.1:3 --from 1
# ---- end of the orbit diagram and basin block ----

# ---- the analyses' remaining literals are keys ----
expect_usage_error friction-factor-fraction "--set: key 'analysis.friction.transient_factors' = '2.5'" \
  rimless analysis gait-vs-friction --set "analysis.friction.transient_factors=[1,2.5]"
expect_usage_error friction-steps-zero "key 'analysis.friction.continuation_steps[0]' = '0'" \
  rimless analysis gait-vs-friction --set "analysis.friction.continuation_steps=[0]"
expect_usage_error stagnation-kind-fraction "key 'stagnation.kind_fraction' = '-1'" rimless analysis stagnation \
  --config "$src/configs/rimless-stagnation.yaml" --set stagnation.kind_fraction=-1
expect_usage_error stagnation-fit-offset "key 'stagnation.fit_offset' = '0'" rimless analysis stagnation \
  --config "$src/configs/rimless-stagnation.yaml" --set stagnation.fit_offset=0
expect_usage_error continuation-min-step "key 'analysis.continuation.min_step' = '0'" \
  rimless continuation --model rigid --param rimless.slope --from 0.05 --to 0.15 --set analysis.continuation.min_step=0
expect_usage_error continuation-min-step-order "key 'analysis.continuation.min_step' = '0.5'" \
  rimless continuation --model rigid --param rimless.slope --from 0.05 --to 0.15 --set analysis.continuation.min_step=0.5
# ---- end of the helper-lit block ----

echo "$passed passed, $failed failed"
test "$failed" -eq 0

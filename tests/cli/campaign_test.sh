#!/usr/bin/env bash
# flexgait campaign: bad grids (exit 2, one line naming the key, nothing written); a 2-D rimless
# grid and a small humanoid grid give the same campaign.csv bytes with 1 and 2 threads (and, with
# MODE=mpi, under mpirun -np 3); a point that fails is a row with its reason; kill -9 then --resume
# gives the same bytes, a torn last line included; --resume of a different grid is refused;
# --plot-metrics names only metrics of the experiment and draws a 3-D grid as one figure; axes
# that set the same key, a --seed outside [0, 2^64 - 1] and an --out that cannot hold a campaign
# are refused (exit 2), as is --keep-runs whose logs would exceed --max-run-bytes; a finished campaign is marked `complete`; --resume trusts no garbage row.
# Usage: campaign_test.sh FLEXGAIT_EXE [mpi MPIRUN]
set -u
exe=$1
mode=${2:-threads}
mpirun=${3:-mpirun}
source "$(dirname "$0")/harness.sh"
campaign() { timeout 300 "$exe" campaign "$@" --no-plot >"$work/stdout" 2>"$work/stderr"; }
# As root, OpenMPI's mpirun needs --allow-run-as-root (test harness only); 3 ranks on 2 cores: --oversubscribe.
mpi_campaign() {
  timeout 300 "$mpirun" --allow-run-as-root --oversubscribe -np 3 "$exe" campaign "$@" --no-plot \
    >"$work/stdout" 2>"$work/stderr"
}
# A 2-D rimless grid (rigid wheel: fast) with points that find no gait (slope too small: the wheel rolls back).
rimless_grid=(rimless-fixed-point --set sim.model=rigid --grid rimless.mu=0.3:0.9:4 --grid rimless.slope=0.02:0.1:3)
# A small walking envelope: 2 steps, step length x compensation.
# Soft gears (500 Nm/rad): off falls, both walks (THORMANG3's inertials at 0.723 m walk 2 steps at 1000).
walk_grid=(humanoid-walk --set walk.steps=2 --set plant.k_joint=500 --grid walk.step_length=0.1,0.3
           --grid control.compensation=off,both)
# Random draws crossed with a grid axis, reduced over the draws: the rigid wheel's gait over random slopes.
random_grid=(rimless-fixed-point --set sim.model=rigid --grid rimless.mu=0.3,0.9 --random rimless.slope=0.02:0.12
             --random initial.omega=0.5:1.5 --samples 5 --seed 7 --reduce sample)

if [ "$mode" = mpi ]; then
  campaign "${rimless_grid[@]}" --out "$work/r1" --jobs 1
  mpi_campaign "${rimless_grid[@]}" --out "$work/rm"
  rc=$?
  check "mpirun -np 3 rimless: exit 0 ($(head -c 1000 "$work/stderr"))" test "$rc" -eq 0
  check "mpirun -np 3 rimless: same bytes as 1 thread" cmp -s "$work/r1/campaign.csv" "$work/rm/campaign.csv"
  mpi_campaign "${rimless_grid[@]}" --out "$work/rm2" --jobs 2
  check "mpirun -np 3 --jobs 2 rimless: same bytes as 1 thread" cmp -s "$work/r1/campaign.csv" "$work/rm2/campaign.csv"
  campaign "${walk_grid[@]}" --out "$work/w1" --jobs 1
  mpi_campaign "${walk_grid[@]}" --out "$work/wm"
  check "mpirun -np 3 walk: same bytes as 1 thread" cmp -s "$work/w1/campaign.csv" "$work/wm/campaign.csv"
  campaign "${random_grid[@]}" --out "$work/d1" --jobs 1
  mpi_campaign "${random_grid[@]}" --out "$work/dm" --jobs 2
  check "mpirun -np 3 random draws: same campaign.csv as 1 thread" cmp -s "$work/d1/campaign.csv" "$work/dm/campaign.csv"
  check "mpirun -np 3 random draws: same reduced.csv as 1 thread" cmp -s "$work/d1/reduced.csv" "$work/dm/reduced.csv"
  mpi_campaign "${rimless_grid[@]}" --out "$work/never" --grid rimless.KK=1
  check "mpirun: a bad key exits 2 (got $?)" test $? -eq 2
  check "mpirun: a bad key is said once, by rank 0" test "$(grep -c "rimless.KK" "$work/stderr")" -eq 1
  check "mpirun: a bad key writes nothing" test ! -e "$work/never"
  mpi_campaign "${rimless_grid[@]}" --out "$work/never" --jobs -3
  check "mpirun: a bad option exits 2 (got $?)" test $? -eq 2
  check "mpirun: a bad option is said once" test "$(grep -c "^error: --jobs" "$work/stderr")" -eq 1
  # Ranks 1 and 2 alone fail (as a node that cannot read --config would): all exit 2, rank 0 names rank 1.
  timeout 300 "$mpirun" --allow-run-as-root --oversubscribe -np 1 "$exe" campaign "${rimless_grid[@]}" --no-plot \
    --out "$work/never" : -np 2 "$exe" campaign "${rimless_grid[@]}" --no-plot --out "$work/never" --set rimless.KK=3 \
    >"$work/stdout" 2>"$work/stderr"
  check "mpirun: an error of other ranks only exits 2 (got $?)" test $? -eq 2
  check "mpirun: rank 0 says it once, naming the rank" test "$(grep -c "^error: rank 1: --set: .*rimless.KK" "$work/stderr")" -eq 1
  check "mpirun: an error of other ranks only writes nothing" test ! -e "$work/never"
  mpi_campaign "${rimless_grid[@]}" --grid rimless.K=1000,2000 --out "$work/rm" --resume
  check "mpirun: resume of a different grid refused (workers released)" grep -q "different campaign" "$work/stderr"
  # The orbit diagram spreads its parameter values over the ranks: the same bytes.
  orbit=(rimless analysis orbit-diagram --param rimless.slope --from 0.2 --to 0.2355 --count 7 --transient 30
         --record 6 --no-plot)
  timeout 300 "$exe" "${orbit[@]}" --jobs 1 --out "$work/o1" >/dev/null 2>&1
  timeout 300 "$mpirun" --allow-run-as-root --oversubscribe -np 3 "$exe" "${orbit[@]}" --out "$work/om" \
    >"$work/stdout" 2>"$work/stderr"
  rc=$?
  check "mpirun -np 3 orbit-diagram: exit 0 ($(head -c 1000 "$work/stderr"))" test "$rc" -eq 0
  for f in orbit.csv orbit_points.csv summary.json; do
    check "mpirun -np 3 orbit-diagram: $f the same bytes as 1 thread" cmp -s "$work/o1/$f" "$work/om/$f"
  done
  timeout 300 "$mpirun" --allow-run-as-root --oversubscribe -np 3 "$exe" "${orbit[@]}" --count 1 --out "$work/never" \
    >"$work/stdout" 2>"$work/stderr"
  check "mpirun orbit-diagram: a bad --count exits 2 (got $?)" test $? -eq 2
  check "mpirun orbit-diagram: said once" test "$(grep -c "^error: --count" "$work/stderr")" -eq 1
  check "mpirun orbit-diagram: nothing written" test ! -e "$work/never"
  echo "campaign mpi: $passed passed, $failed failed"
  [ "$failed" -eq 0 ]
  exit
fi

# expect_usage_error NAME NEEDLE ARGS...: exit code 2, stderr one line naming NEEDLE, nothing written.
expect_usage_error() {
  local name=$1 needle=$2
  shift 2
  local out="$work/never-$name"
  campaign "$@" --out "$out"
  local code=$?
  check "$name: exit code 2 (got $code)" test "$code" -eq 2
  check "$name: message names '$needle': $(head -c 1000 "$work/stderr")" grep -qF -- "$needle" "$work/stderr"
  check "$name: one line on stderr" test "$(wc -l <"$work/stderr")" -eq 1
  check "$name: nothing written" test ! -e "$out"
}
expect_usage_error unknown-experiment "rimless-fixed-point" nope --grid rimless.K=1
expect_usage_error unknown-key "rimless.KK" rimless-simulate --grid rimless.K=1000 --grid rimless.KK=1,2
expect_usage_error out-of-domain "rimless.K" rimless-simulate --grid rimless.K=1000,-1
expect_usage_error bad-choice "control.compensation" humanoid-walk --grid control.compensation=off,sometimes
expect_usage_error cross-check "--grid point 1" rimless-simulate --grid rimless.mu_k=0.3,0.9
expect_usage_error no-equals "--grid 'rimless.K'" rimless-simulate --grid rimless.K
expect_usage_error bad-count "count of rimless.K" rimless-simulate --grid rimless.K=1:2:0.5
expect_usage_error bad-range "ends of the range of rimless.K" rimless-simulate --grid rimless.K=a:2:3
expect_usage_error empty-value "empty value of rimless.K" rimless-simulate --grid rimless.K=1,,2
expect_usage_error twice "rimless.K' given twice" rimless-simulate --grid rimless.K=1 --grid rimless.K=2
expect_usage_error bad-set "rimless.KK" rimless-simulate --grid rimless.K=1 --set rimless.KK=2
expect_usage_error bad-reduce "--reduce: 'rimless.mu' is not an axis" rimless-simulate --grid rimless.K=1 \
  --reduce rimless.mu
expect_usage_error bad-random "--random 'rimless.slope=0.2:0.1'" rimless-simulate --random rimless.slope=0.2:0.1 \
  --samples 3
expect_usage_error random-out-of-domain "--random rimless.K" rimless-simulate --random rimless.K=-5:5 --samples 3
expect_usage_error random-and-grid "key 'rimless.K' is also a --grid axis" rimless-simulate --grid rimless.K=1 \
  --random rimless.K=1:2 --samples 3
expect_usage_error random-without-samples "--samples: 0 with --random axes" rimless-simulate --random rimless.K=1:2
expect_usage_error seed-without-random "--seed: given without a --random axis" rimless-simulate --grid rimless.K=1 \
  --seed 3
expect_usage_error no-axis "no --grid or --random axis" rimless-simulate
expect_usage_error push-force-set "disturbance.push.force_x" humanoid-push-recovery \
  --grid push_recovery.direction=left --set disturbance.push.force_x=10
expect_usage_error bad-plot-metric "--plot-metrics: 'nope' is not a metric of humanoid-walk" humanoid-walk \
  --grid walk.step_length=0.1 --plot-metrics fell,nope
# Axes that set the same key (an alias and its parts): the table would list values never run.
expect_usage_error alias-and-part "--grid rimless.mu_s and --grid rimless.mu both set rimless.mu_s" rimless-simulate \
  --grid rimless.mu_s=0.5,0.6 --grid rimless.mu=0.3,0.4
expect_usage_error random-part-of-alias "--grid rimless.mu and --random rimless.mu_k both set rimless.mu_k" \
  rimless-simulate --grid rimless.mu=0.3,0.4 --random rimless.mu_k=0.1:0.2 --samples 2
# --set of a key an axis sets: the axis would replace it at every point (a --config file is the base; allowed).
expect_usage_error set-and-grid "--set rimless.mu_s and --grid rimless.mu_s both set rimless.mu_s" rimless-simulate \
  --set rimless.mu_s=0.9 --grid rimless.mu_s=0.7,0.8
expect_usage_error set-part-and-alias "--set rimless.mu_k and --grid rimless.mu both set rimless.mu_k" rimless-simulate \
  --set rimless.mu_k=0.2 --grid rimless.mu=0.3,0.4
# Seeds outside [0, 2^64 - 1] (CLI11 alone reads -1 and 2^64 as 2^64 - 1).
expect_usage_error seed-negative "--seed: '-1' is not an integer in [0, 18446744073709551615]" rimless-simulate \
  --random rimless.slope=0.02:0.1 --samples 2 --seed -1
expect_usage_error seed-2-to-64 "--seed: '18446744073709551616' is not an integer in [0, 18446744073709551615]" \
  rimless-simulate --random rimless.slope=0.02:0.1 --samples 2 --seed 18446744073709551616
expect_usage_error seed-fraction "--seed: '1.5' is not an integer" rimless-simulate --random rimless.slope=0.02:0.1 \
  --samples 2 --seed 1.5
# --out that cannot hold a campaign: exit 2 before any point, the target untouched.
cheap_grid=(rimless-simulate --set sim.model=rigid --set sim.steps=1 --grid rimless.slope=0.05,0.1)
expect_bad_out() {  # expect_bad_out NAME NEEDLE OUT
  campaign "${cheap_grid[@]}" --out "$3"
  local code=$?
  check "$1: exit code 2 (got $code)" test "$code" -eq 2
  check "$1: message names '$2': $(head -c 1000 "$work/stderr")" grep -qF -- "$2" "$work/stderr"
  check "$1: one line on stderr" test "$(wc -l <"$work/stderr")" -eq 1
}
printf 'mine\n' >"$work/a_file"
expect_bad_out out-is-file "--out: cannot make the run directory $work/a_file: it is a regular file, not a directory" "$work/a_file"
check "out-is-file: the file untouched" test "$(cat "$work/a_file")" = mine
expect_bad_out out-under-file "--out: cannot make the run directory $work/a_file/run" "$work/a_file/run"
expect_bad_out out-dev-null "--out: cannot make the run directory /dev/null: it is a character device, not a directory" /dev/null
check "out-dev-null: /dev/null still a character device" test -c /dev/null
mkdir -p "$work/with_fifo" && mkfifo "$work/with_fifo/campaign.csv"
expect_bad_out out-holds-fifo "it holds campaign.csv, which is a FIFO (named pipe)" "$work/with_fifo"
check "out-holds-fifo: nothing written" test "$(ls -A "$work/with_fifo")" = campaign.csv
check "out-holds-fifo: still a FIFO" test -p "$work/with_fifo/campaign.csv"

if [ -n "${FLEXGAIT_BUILT_WITHOUT_MPI:-}" ]; then  # as if started by mpirun -np 2
  OMPI_COMM_WORLD_SIZE=2 expect_usage_error mpi-without-mpi "built without MPI" rimless-simulate --grid rimless.K=1000
fi

# Threads: the same bytes with 1 and 2; every point a row; failures as rows with their reason.
campaign "${rimless_grid[@]}" --out "$work/r1" --jobs 1
check "rimless --jobs 1: exit 0" test $? -eq 0
campaign "${rimless_grid[@]}" --out "$work/r2" --jobs 2
check "rimless --jobs 2: same bytes" cmp -s "$work/r1/campaign.csv" "$work/r2/campaign.csv"
check "rimless: a row per point (12) and the header" test "$(wc -l <"$work/r1/campaign.csv")" -eq 13
check "rimless: the directory marked complete" test -f "$work/r1/complete"
check "rimless: header is index, axes, then fixed_point.json's keys" \
  grep -q "^index,rimless.mu,rimless.slope,converged,iterations,residual," "$work/r1/campaign.csv"
check "rimless: a point without a gait is a row with its reason" grep -q "^0,0.3,0.02,false,.*rolled back" "$work/r1/campaign.csv"
"$exe" rimless fixed-point --config "$work/r1/config.yaml" --out "$work/fp" --no-plot >/dev/null
check "config.yaml loads back as --config" test $? -eq 0
check "config.yaml names the axes" grep -q "^#   --grid rimless.mu=0.3:0.9:4" "$work/r1/config.yaml"
if /usr/bin/python3 -c "import matplotlib" 2>/dev/null; then  # the figure (python/plot_campaign.py)
  timeout 300 "$exe" campaign "${rimless_grid[@]}" --out "$work/rp" >/dev/null 2>&1
  check "2-D grid: campaign.png drawn" test -s "$work/rp/campaign.png"
  # --plot-metrics on a 3-D grid: one figure, the third axis as its rows (the walking envelope's).
  timeout 300 "$exe" campaign humanoid-walk --set walk.steps=2 --grid walk.step_length=0.1,0.3 \
    --grid walk.step_time=0.6,0.8 --grid control.compensation=off,both --plot-metrics fell,pelvis_roll_error_max \
    --out "$work/wp" >/dev/null 2>&1
  check "3-D grid with --plot-metrics: one campaign.png" test -s "$work/wp/campaign.png"
  check "3-D grid with --plot-metrics: not split by the third axis" test -z "$(ls "$work/wp" | grep 'campaign_')"
fi
campaign "${walk_grid[@]}" --out "$work/w1" --jobs 1
campaign "${walk_grid[@]}" --out "$work/w2" --jobs 2
check "walk --jobs 2: same bytes" cmp -s "$work/w1/campaign.csv" "$work/w2/campaign.csv"
# (k = 500 without compensation: the stance leg sags and the first step's swing sole is still above
# the floor when the next step lifts — a missed step, not a walk; with 0.3 m steps the robot tips over)
check "walk: a missed step is a row with its outcome and reason" \
  grep -q "^0,0.1,off,missed_step,off,full,off,true,a step did not land" "$work/w1/campaign.csv"
check "walk: a fall is a row with its outcome and reason" \
  grep -q "^2,0.3,off,pelvis_tilted,off,full,off,true,pelvis tilted" "$work/w1/campaign.csv"
check "walk: with compensation it walks" grep -q "^3,0.3,both,walked,both,full,both-dynamic-horizontal-lag,false,," \
  "$work/w1/campaign.csv"
campaign humanoid-push-recovery --grid push_recovery.direction=forward --set push_recovery.tolerance=30 \
  --set push_recovery.settle_time=1.5 --out "$work/p1"
check "push recovery: a row with the push's time, recovered, fell_at, bound ($(head -c 300 "$work/stderr"))" \
  grep -qE "^0,forward,standing,forward,4,[0-9.]+,[0-9.]+,[0-9.]+,[0-9.]+,3,$" "$work/p1/campaign.csv"
campaign humanoid-bench --grid plant.k_joint=500,1000 --out "$work/b1" --keep-runs
check "bench campaign with --keep-runs: a run directory per point" test -f "$work/b1/runs/000001/summary.json"
# The kept runs' projected size is checked before anything runs: two 100-step walks keep ~17 MB of
# logs (3 kB a row every 20 ms over ~100 s each), above a cap of 1 MB.
campaign humanoid-walk --grid walk.steps=100,200 --keep-runs --max-run-bytes 1e6 --out "$work/k1"
rc=$?
check "--keep-runs over --max-run-bytes: exit 2 (got $rc)" test "$rc" -eq 2
check "--keep-runs over --max-run-bytes: one line naming both and the size needed" \
  grep -qE "^error: --keep-runs: .* above --max-run-bytes = 1e\+06; .* at least [0-9.e+]+$" "$work/stderr"
check "--keep-runs over --max-run-bytes: nothing written" test ! -e "$work/k1"

# Random draws: the same bytes with 1 and 2 threads; sample s draws the same values at every grid
# point; reduced.csv has a row per mu with the points of its 5 samples.
campaign "${random_grid[@]}" --out "$work/d1" --jobs 1
rc=$?
check "random draws: exit 0 ($(head -c 1000 "$work/stderr"))" test "$rc" -eq 0
campaign "${random_grid[@]}" --out "$work/d2" --jobs 2
check "random draws --jobs 2: same bytes" cmp -s "$work/d1/campaign.csv" "$work/d2/campaign.csv"
check "random draws: header is index, axes, sample, the drawn keys, metrics" \
  grep -q "^index,rimless.mu,sample,rimless.slope,initial.omega,converged," "$work/d1/campaign.csv"
check "random draws: sample s has the same draws at mu = 0.3 and 0.9" test \
  "$(cut -d, -f3-5 "$work/d1/campaign.csv" | sed -n 2,6p)" = "$(cut -d, -f3-5 "$work/d1/campaign.csv" | sed -n 7,11p)"
check "random draws: config.yaml names the draws" grep -q "^#   --random rimless.slope=0.02:0.12" "$work/d1/config.yaml"
check "reduced.csv: a row per mu, 5 points each" \
  test "$(cut -d, -f1-2 "$work/d1/reduced.csv" | tr '\n' ' ')" = "rimless.mu,points 0.3,5 0.9,5 "
campaign "${random_grid[@]::${#random_grid[@]}-4}" --seed 8 --reduce sample --out "$work/d3"
check "random draws: another seed draws other values" test \
  "$(cut -d, -f4 "$work/d1/campaign.csv")" != "$(cut -d, -f4 "$work/d3/campaign.csv")"
campaign "${random_grid[@]::${#random_grid[@]}-4}" --seed 9 --out "$work/d1" --resume
check "resume with another seed: refused (exit 2)" test $? -eq 2
campaign "${random_grid[@]::${#random_grid[@]}-2}" --reduce rimless.mu --out "$work/d1" --resume
check "resume with another --reduce: allowed, nothing recomputed" grep -q " 0 computed, 10 resumed" "$work/stdout"
check "another --reduce: reduced.csv over mu" test "$(head -c 12 "$work/d1/reduced.csv")" = "sample,point"

# kill -9 in the middle, then --resume: the same bytes; a torn last line is computed again.
long_grid=(humanoid-walk --set walk.steps=2 --grid walk.step_length=0.1,0.2,0.3 --grid control.compensation=off,both)
campaign "${long_grid[@]}" --out "$work/k0" --jobs 1
"$exe" campaign "${long_grid[@]}" --out "$work/k1" --jobs 1 --no-plot >/dev/null 2>&1 &
pid=$!
for _ in $(seq 1 6000); do  # until a point or two is done (at most a minute: sanitizer builds are slow)
  [ "$(cat "$work/k1/campaign.partial.csv" 2>/dev/null | wc -l)" -ge 2 ] && break
  sleep 0.01
done
kill -9 "$pid" 2>/dev/null
wait "$pid" 2>/dev/null
check "killed before the end: no campaign.csv yet" test ! -e "$work/k1/campaign.csv"
check "killed before the end: not marked complete" test ! -e "$work/k1/complete"
printf '5,0.3,bo' >>"$work/k1/campaign.partial.csv"  # a torn last line
campaign "${long_grid[@]}" --out "$work/k1" --jobs 2 --resume
check "resume: exit 0" test $? -eq 0
check "resume: some points kept ($(head -n 1 "$work/stdout"))" grep -q " [1-9][0-9]* resumed" "$work/stdout"
check "resume after kill -9: same bytes" cmp -s "$work/k0/campaign.csv" "$work/k1/campaign.csv"
check "resume: marked complete" test -f "$work/k1/complete"
# A partial file whose rows have the right cell count and garbage values: none is trusted.
# Every row of k0 with one cell damaged (an axis value, a number, a boolean) or another point's
# values under its index; the resume computes them all again and gives the same bytes.
mkdir -p "$work/k2"
cp "$work/k1/campaign.signature" "$work/k2/"
/usr/bin/python3 - "$work/k0/campaign.csv" "$work/k2/campaign.partial.csv" <<'PY'
import csv, sys
rows = list(csv.reader(open(sys.argv[1], newline="")))
header, rows = rows[0], rows[1:]
fell, roll = header.index("fell"), header.index("pelvis_roll_error_max")
damage = [(1, "0.7"), (2, "sideways"), (fell, "maybe"), (roll, "nan"), (roll, "1e999"), (0, "0")]
for row, (column, text) in zip(rows, damage):
    row[column] = text
csv.writer(open(sys.argv[2], "w", newline=""), lineterminator="\n").writerows(rows)
PY
campaign "${long_grid[@]}" --out "$work/k2" --jobs 2 --resume
check "garbage rows: exit 0" test $? -eq 0
check "garbage rows: none trusted ($(head -n 1 "$work/stdout"))" grep -q " 6 computed, 0 resumed" "$work/stdout"
check "garbage rows: the note says campaign" grep -q "not finished points of this campaign" "$work/stderr"
check "garbage rows: same bytes" cmp -s "$work/k0/campaign.csv" "$work/k2/campaign.csv"
cp "$work/k1/campaign.csv" "$work/k1.csv"
campaign humanoid-walk --set walk.steps=2 --grid walk.step_length=0.1,0.2 --grid control.compensation=off,both \
  --out "$work/k1" --resume
check "resume of different axes: exit 2" test $? -eq 2
check "resume of different axes: says so" grep -q "holds a different campaign" "$work/stderr"
check "resume of different axes: the campaign left as it was" cmp -s "$work/k0/campaign.csv" "$work/k1/campaign.csv"
campaign "${long_grid[@]}" --set walk.swing_height=0.041 --out "$work/k1" --resume
check "resume of a different base configuration: exit 2" test $? -eq 2
campaign "${long_grid[@]}" --out "$work/nothing" --resume
check "resume where there is no campaign: exit 2" test $? -eq 2
check "resume where there is no campaign: says campaign" grep -q "no campaign to resume" "$work/stderr"

echo "campaign: $passed passed, $failed failed"
[ "$failed" -eq 0 ]

#!/usr/bin/env bash
# Messages and output of the first contact: `--set` takes the alias rimless.mu as --grid and
# --param do, and `flexgait schema` lists it; an unknown key's did-you-mean offers keys of the same quantity only; a check that
# fails on a default names the value given against it and what to change, and no message starts
# with "default:"; a finished campaign is marked complete; the stages
# without a progress bar (drawing figures) are announced on a terminal only; continuation and
# robustness show a progress bar there.
# Usage: messages_test.sh FLEXGAIT_EXE
set -u
exe=$1
source "$(dirname "$0")/harness.sh"
cd "$work" || exit 1

# The alias: the same run as its two parts, and config.yaml holds the parts.
"$exe" rimless simulate --steps 2 --no-plot --set rimless.mu=0.13 --out alias >/dev/null 2>"$work/err"
check "--set rimless.mu=0.13 exits 0" test $? -eq 0
"$exe" rimless simulate --steps 2 --no-plot --set rimless.mu_s=0.13 --set rimless.mu_k=0.13 --out parts >/dev/null 2>&1
check "rimless.mu: the same summary.json as mu_s and mu_k" cmp -s alias/summary.json parts/summary.json
check "rimless.mu: the same config.yaml as mu_s and mu_k" cmp -s alias/config.yaml parts/config.yaml
check "config.yaml holds mu_s" grep -q "mu_s: 0.13" alias/config.yaml
printf 'rimless:\n  mu: 0.13\n' >alias.yaml
"$exe" rimless simulate --steps 2 --no-plot --config "$work/alias.yaml" --out alias-file >/dev/null 2>&1
check "rimless: {mu: 0.13} in a file: the same config.yaml" cmp -s alias/config.yaml alias-file/config.yaml
"$exe" rimless simulate --steps 2 --no-plot --set rimless.mu=-1 --out never >/dev/null 2>"$work/err"
check "rimless.mu=-1: exit 2" test $? -eq 2
check "rimless.mu=-1: the message names the alias and the value" grep -qF "key 'rimless.mu' = '-1'" "$work/err"
check "nothing written for a refused alias value" test ! -e never
"$exe" schema >schema.json
check "schema lists the alias rimless.mu and its parts" /usr/bin/python3 -c "
import json
aliases = json.load(open('schema.json'))['aliases']['rimless']
assert {'key': 'rimless.mu', 'parts': ['rimless.mu_s', 'rimless.mu_k']} == {k: aliases[0][k] for k in ('key', 'parts')}"

# Did-you-mean: the nearest names of the same quantity, never the mass for a friction typo.
"$exe" rimless simulate --steps 2 --no-plot --set rimless.mux=0.1 --out never >/dev/null 2>"$work/err"
check "rimless.mux: exit 2" test $? -eq 2
check "rimless.mux: one line" test "$(wc -l <"$work/err")" -eq 1
check "rimless.mux: did you mean rimless.mu" grep -qF "did you mean 'rimless.mu'?" "$work/err"
check "rimless.mux: not the mass rimless.m" bash -c "! grep -qF \"'rimless.m'\" '$work/err'"
"$exe" rimless simulate --steps 2 --no-plot --set nope=1 --out never >/dev/null 2>"$work/err"
check "nope: exit 2 saying where the keys are listed" grep -qF "flexgait schema" "$work/err"

# Lowering mu_s alone: blamed on the --set, and says what to change.
"$exe" rimless simulate --steps 2 --no-plot --set rimless.mu_s=0.1 --out never >/dev/null 2>"$work/err"
check "mu_s below the default mu_k: exit 2" test $? -eq 2
check "mu_s below mu_k: the message leads with --set" grep -qE "^(error: )?--set: key 'rimless.mu_k'" "$work/err"
check "mu_s below mu_k: says what to change" grep -qF "set both with rimless.mu" "$work/err"
check "no message starts with default:" bash -c "! grep -qE '^(error: )?default:' '$work/err'"

# A finished campaign: complete (its partial file stays: --resume with another --reduce reads it);
# its alias axis ran both coefficients.
"$exe" campaign rimless-simulate --set sim.steps=2 --grid rimless.mu=0.13,0.6 --no-plot --out camp >/dev/null 2>&1
check "campaign over rimless.mu exits 0" test $? -eq 0
check "campaign: complete marker" test -f camp/complete
check "campaign: 2 rows" test "$(wc -l <camp/campaign.csv)" -eq 3

# Stages without a progress bar are announced on a terminal, and only there.
"$exe" rimless simulate --steps 2 --out plotted >/dev/null 2>"$work/err"
check "off a terminal: no stage line" bash -c "! grep -qF 'drawing the figures' '$work/err'"
if script -qec true /dev/null >/dev/null 2>&1; then
  script -qec "'$exe' rimless simulate --steps 2 --out plotted-tty 2>&1" /dev/null >"$work/tty" 2>&1
  check "on a terminal: drawing the figures is said" grep -qF "drawing the figures (plot_rimless.py)" "$work/tty"
  # Long analyses show a bar from their start: continuation over the interval's fraction reached,
  # robustness over the perturbations tried.
  script -qec "'$exe' rimless continuation --param rimless.slope --from 0.1 --to 0.11 --no-plot --out cont 2>&1" \
    /dev/null >"$work/tty" 2>&1
  check "on a terminal: continuation shows its progress" grep -qF "/100 % of the interval" "$work/tty"
  script -qec "'$exe' rimless analysis robustness --mu 0.6 --set analysis.robustness.epsilon_count=2 --no-plot \
    --out robust 2>&1" /dev/null >"$work/tty" 2>&1
  check "on a terminal: robustness shows its progress" grep -qF "100/100 % of the perturbations" "$work/tty"
fi

echo "$passed passed, $failed failed"
test "$failed" -eq 0

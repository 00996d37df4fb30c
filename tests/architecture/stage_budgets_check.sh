#!/usr/bin/env bash
# The test command's stage timing (tools/ci/stage_timing.sh, tools/ci/stage-budgets.txt):
#   1. every stage tools/run-tests.sh runs has a budget row, and every row names a stage it runs;
#   2. a stage forced over its budget prints the warning naming it, and the summary marks it;
#   3. a stage within its budget prints no warning; a failing stage still returns its exit status.
# Usage: stage_budgets_check.sh SOURCE_DIR WORK_DIR      prints PASS or the first failure
set -uo pipefail
src=$1 work=$2
fail() { echo "FAIL: $*"; exit 1; }
rm -rf "$work" && mkdir -p "$work"

budgets=$src/tools/ci/stage-budgets.txt
run_stages=$(sed -n 's/^stage \([a-z-]*\) .*/\1/p' "$src/tools/run-tests.sh" | sort)
budget_rows=$(awk '$1 !~ /^#/ && NF >= 2 { print $1 }' "$budgets" | sort)
[ -n "$run_stages" ] || fail "no 'stage NAME' lines in tools/run-tests.sh"
[ "$run_stages" = "$budget_rows" ] ||
  fail "stages of tools/run-tests.sh ($(echo $run_stages)) differ from the rows of tools/ci/stage-budgets.txt ($(echo $budget_rows))"
awk '$1 !~ /^#/ && NF >= 2 && $2 !~ /^[0-9]+$/ { print "bad budget: " $0; bad = 1 } END { exit bad }' "$budgets" ||
  fail "a budget is not a whole number of seconds"

printf 'slow 0\nquick 60\nbroken 60\n' >"$work/budgets.txt"
SPREAD_STAGE_BUDGETS=$work/budgets.txt bash -c '
  . "$1/tools/ci/stage_timing.sh"
  stage slow sleep 1.2
  stage quick true
  stage broken sh -c "exit 3"; echo "broken returned $?"
  stage_summary' _ "$src" >"$work/out.txt" 2>&1
grep -q "STAGE OVER BUDGET: 'slow' took [12] s, its budget is 0 s" "$work/out.txt" || { cat "$work/out.txt"; fail "no warning for the slow stage"; }
grep -q "STAGE OVER BUDGET: 'quick'" "$work/out.txt" && { cat "$work/out.txt"; fail "a warning for a stage within its budget"; }
grep -q "broken returned 3" "$work/out.txt" || { cat "$work/out.txt"; fail "a failing stage lost its exit status"; }
grep -q "slow .* OVER BUDGET" "$work/out.txt" || { cat "$work/out.txt"; fail "the summary does not mark the slow stage"; }
grep -Eq "^  total +[0-9]+ s  \(budgets 120 s\)" "$work/out.txt" || { cat "$work/out.txt"; fail "no total in the summary"; }
echo PASS

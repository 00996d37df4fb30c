#!/usr/bin/env bash
# Stage timing for the test command (tools/run-tests.sh): each stage's wall time against its budget in
# tools/ci/stage-budgets.txt (or $SPREAD_STAGE_BUDGETS). A stage over its budget prints a loud warning naming
# it, so the commit that grows a stage is the one whose run shows it. Time never fails the run: these
# machines are noisy; a failing stage fails it as before.
#
# Sourced, not run:   . tools/ci/stage_timing.sh
#   stage NAME CMD...  runs CMD, records its wall time, prints it against the budget; returns CMD's status
#   stage_summary      prints every stage run so far, the total and the budgets' total
stage_budgets_file=${SPREAD_STAGE_BUDGETS:-$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)/stage-budgets.txt}
stage_names=()
stage_seconds=()
stage_started=$SECONDS

# The budget of stage $1 in seconds, empty when the file has no row for it.
stage_budget() {
  [ -f "$stage_budgets_file" ] || return 0
  awk -v s="$1" '$1 !~ /^#/ && $1 == s { print $2; exit }' "$stage_budgets_file"
}

stage_line() {  # name seconds → "name  123 s  (budget 150 s)" and, when over, the warning on its own lines
  local name=$1 took=$2 budget
  budget=$(stage_budget "$name")
  if [ -z "$budget" ]; then
    printf '  %-18s %5d s  (no budget in %s)\n' "$name" "$took" "$stage_budgets_file"
  elif [ "$took" -gt "$budget" ]; then
    printf '  %-18s %5d s  (budget %d s) OVER BUDGET\n' "$name" "$took" "$budget"
  else
    printf '  %-18s %5d s  (budget %d s)\n' "$name" "$took" "$budget"
  fi
}

stage_warn_if_over() {
  local name=$1 took=$2 budget
  budget=$(stage_budget "$name")
  if [ -n "$budget" ] && [ "$took" -gt "$budget" ]; then
    {
      echo "################################################################################"
      echo "### STAGE OVER BUDGET: '$name' took $took s, its budget is $budget s"
      echo "### ($stage_budgets_file). Find what grew it in this commit, or raise the budget"
      echo "### there with the reason in the commit message."
      echo "################################################################################"
    } >&2
  fi
}

stage() {
  local name=$1; shift
  local start=$SECONDS status=0
  echo "=== stage $name: $*"
  "$@" || status=$?
  local took=$((SECONDS - start))
  stage_names+=("$name")
  stage_seconds+=("$took")
  echo "=== stage $name: $took s$([ "$status" -eq 0 ] || echo ", FAILED (exit $status)")"
  stage_warn_if_over "$name" "$took"
  return "$status"
}

stage_summary() {
  local i total=$((SECONDS - stage_started)) budget_total=0 b over=()
  echo "=== stage times (wall)"
  for i in "${!stage_names[@]}"; do
    stage_line "${stage_names[$i]}" "${stage_seconds[$i]}"
    b=$(stage_budget "${stage_names[$i]}")
    budget_total=$((budget_total + ${b:-0}))
    if [ -n "$b" ] && [ "${stage_seconds[$i]}" -gt "$b" ]; then over+=("${stage_names[$i]}"); fi
  done
  printf '  %-18s %5d s  (budgets %d s)\n' total "$total" "$budget_total"
  if [ ${#over[@]} -gt 0 ]; then
    echo "### OVER BUDGET: ${over[*]} (see the warnings above)" >&2
  fi
}

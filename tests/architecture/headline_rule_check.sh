#!/usr/bin/env bash
# The headline working-width rule is one sentence, said the same way wherever a user or an integrator
# reads it: the C header, the prediction's header, docs/metrics.md (where its sources are) and
# docs/c-api.md. Comment markers and line breaks are ignored; a file that words the rule differently fails.
set -uo pipefail
root=${1:?usage: headline_rule_check.sh SOURCE_DIR}
rule="upper end of the widest band of bout widths with CV <= target whose lowest CV meets the target at 95 % confidence, or that is joined to such a band by gaps the samples do not show above the target (the first band when none is)"
status=0
for file in capi/include/spread/spread.h libspread/analysis/predict/prediction.hpp docs/metrics.md docs/c-api.md; do
  # One line of text: comment markers (/* */ // *) and runs of white space become one space.
  flat=$(sed -e 's#/\*##g; s#\*/##g; s#//##g; s#^[[:space:]]*\*[[:space:]]# #' "$root/$file" | tr '\n' ' ' | tr -s '[:space:]' ' ')
  if [[ "$flat" != *"$rule"* ]]; then
    echo "FAIL: $file does not state the headline rule as: $rule"
    status=1
  fi
done
[ $status -eq 0 ] && echo "PASS: the headline rule reads the same in all four places"
exit $status

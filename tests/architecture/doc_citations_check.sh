#!/usr/bin/env bash
# tools/check_doc_citations.py must fail on a tree whose comments cite a page it does not hold or a section
# its design page lacks, naming each with its file and line, and pass once they are there.
# Usage: doc_citations_check.sh PYTHON CHECK WORK_DIR      prints PASS or the first failure
set -uo pipefail
python=$1 check=$2 work=$3
fail() { echo "FAIL: $*"; exit 1; }
rm -rf "$work" && mkdir -p "$work/docs" "$work/src"
md=md  # the fixture's names are put together, so that this script cites nothing itself
printf '# Design\n## 1. One\n' >"$work/docs/design.$md"
printf '// as in DESIGN.%s, and docs/design.%s §1\nint x;  // docs/design.%s §7\n' $md $md $md >"$work/src/a.cpp"
"$python" "$check" --root "$work" >"$work/out.txt" 2>&1
status=$?
[ $status -eq 1 ] || { cat "$work/out.txt"; fail "exit status $status, expected 1"; }
grep -q "^src/a.cpp:1: DESIGN.$md: no such document in the tree" "$work/out.txt" || { cat "$work/out.txt"; fail "the missing page not named"; }
grep -q "^src/a.cpp:2: docs/design.$md §7: docs/design.$md has no section 7" "$work/out.txt" ||
  { cat "$work/out.txt"; fail "the missing section not named"; }
grep -q "src/a.cpp:1: docs/design.$md §1" "$work/out.txt" && { cat "$work/out.txt"; fail "a section that exists was refused"; }
printf '# Design\n## 1. One\n## 7. Seven\n' >"$work/docs/design.$md"
printf 'notes\n' >"$work/DESIGN.$md"
"$python" "$check" --root "$work" >"$work/out.txt" 2>&1 || { cat "$work/out.txt"; fail "a complete tree was refused"; }
grep -q "3 citations of 2 documents checked, 0 missing" "$work/out.txt" || { cat "$work/out.txt"; fail "wrong count"; }
echo PASS

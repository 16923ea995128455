#!/usr/bin/env bash
# Every study file (studies/*.prm, tests/study/*.prm) passes anvil --study --check:
# its syntax, its scene and every ladder level with anvil --check (~30 anvil
# start-ups, so labelled long; parse_all_prm checks the study tests' scenes).
set -u
anvil="$1"; src="$2"
fail=0
for f in "$src"/studies/*.prm "$src"/tests/study/*.prm; do
  grep -q "^subsection Study" "$f" || continue
  if out=$("$anvil" --study "$f" --check 2>&1); then echo "PASS  $out"; else echo "FAIL  $f: $out"; fail=1; fi
done
exit $fail

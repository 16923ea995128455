#!/usr/bin/env bash
# Every shipped scene (prm/*.prm), and test scene parses and checks against its mesh.
set -u
anvil="$1"; src="$2"
fail=0
for f in "$src"/prm/*.prm "$src"/tests/*.prm "$src"/contrib/steps/*/*.prm; do
  [ -f "$f" ] || continue
  # A step program's own files (parts it registers itself, material-point files) are read by it.
  grep -q "^# Read by its step program" "$f" && { echo "SKIP  $f: read by its step program"; continue; }
  if out=$(cd "$(dirname "$f")" && "$anvil" "$f" --check 2>&1); then echo "PASS  $out"; else echo "FAIL  $f: $out"; fail=1; fi
done
# The scenes of the study tests (study files themselves: tests/study_files.sh, label long).
for f in "$src"/tests/study/*.prm; do
  grep -q "^subsection Study" "$f" && continue
  if out=$("$anvil" "$f" --check 2>&1); then echo "PASS  $out"; else echo "FAIL  $f: $out"; fail=1; fi
done
"$anvil" --print-parameters > /dev/null || { echo "FAIL  --print-parameters"; fail=1; }
"$anvil" --help | grep -q "Polynomial degree" || { echo "FAIL  --help lacks parameters"; fail=1; }
exit $fail

#!/usr/bin/env bash
# Regenerates doc/studies/: runs the studies of studies/ (all, or those given)
# with the build's anvil and copies their tables and figures to
# doc/studies/<study>/. Runs a study already has are reused (delete
# output/study/<study> to measure again). doc/studies/<study>.md discusses them.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BUILD="${ANVIL_BUILD:-$ROOT/build}"
[ -x "$BUILD/anvil-study" ] || { echo "studies.sh: no $BUILD/anvil-study (build anvil first: contrib/run.sh)" >&2; exit 2; }
cd "$ROOT"
studies=("$@")
[ ${#studies[@]} -gt 0 ] || studies=(studies/*.prm)
for s in "${studies[@]}"; do
  name="$(basename "$s" .prm)"
  out="output/study/$name"
  "$BUILD/anvil" --study "$s" --output "$out"
  mkdir -p "doc/studies/$name"
  for f in "$out"/*.md "$out"/*.csv "$out"/*.png; do
    [ -e "$f" ] && cp "$f" "doc/studies/$name/"
  done
done

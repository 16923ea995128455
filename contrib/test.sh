#!/usr/bin/env bash
# Quick start, command 2: set up, build and run the tests.
#   contrib/test.sh            # everything CI runs (skips tests labelled long and bench)
#   contrib/test.sh --all      # long tests too
#   contrib/test.sh -R shear   # extra arguments go to ctest
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
args=(-LE "long|bench")
if [ "${1:-}" = "--all" ]; then args=(-LE bench); shift; fi
cd "$ANVIL_BUILD"
exec ctest --output-on-failure -j2 "${args[@]}" "$@"

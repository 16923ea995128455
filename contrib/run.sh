#!/usr/bin/env bash
# Quick start, command 1: set up, build and run a scene (default: the shipped main scene).
#   contrib/run.sh [scene.prm] [--set 'Section/Entry=value' ...]
#   ANVIL_NP=2 contrib/run.sh prm/cantilever.prm     # under mpirun with 2 processes
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
scene="${1:-$ANVIL_ROOT/prm/cantilever.prm}"
[ $# -gt 0 ] && shift
if [ "${ANVIL_NP:-1}" -gt 1 ]; then
  exec mpirun -np "$ANVIL_NP" "$ANVIL_BUILD/anvil" "$scene" "$@"
fi
exec "$ANVIL_BUILD/anvil" "$scene" "$@"

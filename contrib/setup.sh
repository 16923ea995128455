#!/usr/bin/env bash
# Installs what anvil needs (Debian packages) and builds it if anything is stale.
# Sourced by contrib/run.sh, contrib/test.sh and contrib/bench.sh; run alone it just builds.
set -euo pipefail
ANVIL_ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
ANVIL_BUILD="${ANVIL_BUILD:-$ANVIL_ROOT/build}"
# python3-matplotlib, -numpy and -vtk9: anvil-plot and anvil-render (Output/Figures).
packages=(libdeal.ii-dev gmsh numdiff cmake make g++ openmpi-bin ccache python3
          python3-matplotlib python3-numpy python3-vtk9)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  if [ "$(id -u)" = 0 ]; then
    echo "anvil: installing ${missing[*]}" >&2
    export DEBIAN_FRONTEND=noninteractive
    apt-get update -q >&2
    apt-get install -y -q --no-install-recommends "${missing[@]}" >&2
  else
    echo "anvil: missing packages; run as root:" >&2
    echo "  apt-get update && apt-get install -y --no-install-recommends ${missing[*]}" >&2
    exit 1
  fi
fi

# MPI as root (CI, containers) needs these.
if [ "$(id -u)" = 0 ]; then
  export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
fi
export OMPI_MCA_rmaps_base_oversubscribe=1

# ANVIL_SKIP_BUILD=1: use the build as it is (tests/quick_start.py, run by
# ctest after the build).
if [ -n "${ANVIL_SKIP_BUILD:-}" ]; then
  return 0 2>/dev/null || exit 0
fi
if [ ! -f "$ANVIL_BUILD/CMakeCache.txt" ]; then
  cmake -S "$ANVIL_ROOT" -B "$ANVIL_BUILD" -DCMAKE_BUILD_TYPE=Release >&2
fi
cmake --build "$ANVIL_BUILD" -j2 >&2

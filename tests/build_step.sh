#!/usr/bin/env bash
# Build a step program out of tree against anvil's build directory and run it.
set -eu
step_src="$1"; anvil_build="$2"; work="$3"
mkdir -p "$work"
cmake -S "$step_src" -B "$work" -Danvil_DIR="$anvil_build" -DCMAKE_BUILD_TYPE=Release > "$work/configure.log"
cmake --build "$work" -j2 > "$work/build.log" || { cat "$work/build.log"; exit 1; }
cd "$work"
exe=$(basename "$step_src")
exec "./$exe" "$step_src/$exe.prm"

#!/usr/bin/env bash
# Build a step program out of tree against anvil's build directory and run it.
set -eu
step_src="$1"; anvil_build="$2"; work="$3"
mkdir -p "$work"
# No -DCMAKE_BUILD_TYPE: the step must take anvil's (anvilConfig.cmake).
rm -f "$work/CMakeCache.txt"
cmake -S "$step_src" -B "$work" -Danvil_DIR="$anvil_build" > "$work/configure.log"
build_type() { sed -n 's/^CMAKE_BUILD_TYPE:[A-Z]*=//p' "$1/CMakeCache.txt"; }
if [ "$(build_type "$work")" != "$(build_type "$anvil_build")" ]; then
  echo "FAIL  step configured as '$(build_type "$work")', anvil was built as '$(build_type "$anvil_build")'"
  exit 1
fi
echo "PASS  configured without CMAKE_BUILD_TYPE: $(build_type "$work"), as anvil"
cmake --build "$work" -j2 > "$work/build.log" || { cat "$work/build.log"; exit 1; }
cd "$work"
exe=$(basename "$step_src")
exec "./$exe" "$step_src/$exe.prm"

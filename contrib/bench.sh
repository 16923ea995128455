#!/usr/bin/env bash
# Benchmark (prints figures, asserts nothing): assembly throughput, linear solve
# time, memory per DoF and Newton iterations for 2D and 3D elastic scenes.
#   contrib/bench.sh            # 2D 512x512 (0.5 M DoFs) and 3D 69^3 (1 M DoFs), one process
#   contrib/bench.sh --small    # quick sizes
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
out="${ANVIL_BENCH_DIR:-$ANVIL_BUILD/bench}"
mkdir -p "$out"
n2=512; n3=69
if [ "${1:-}" = "--small" ]; then n2=128; n3=20; fi
export DEAL_II_NUM_THREADS=1
run() { # name dim blocks
  /usr/bin/time -f "%e s wall, %M KB peak" "$ANVIL_BUILD/anvil" "$ANVIL_ROOT/contrib/bench/elastic_block.prm" \
    --set "Dimension=$2" --set "Geometry/Blocks=$3" --set "Output/Directory=$out/$1" \
    ${4:+--set "$4"} 2> "$out/$1.time"
}
run 2d 2 "body: 0, 0, 1, 1, $n2, $n2"
run 3d 3 "body: 0, 0, 0, 1, 1, 1, $n3, $n3, $n3" \
  "Boundary conditions/Displacement=front: ux = 0, uy = 0, uz = 0; back: uz = -0.05*t"
python3 - "$out" <<'PY'
import json, sys
out = sys.argv[1]
print("%-4s %10s %9s %14s %12s %12s %12s %8s" % ("case", "DoFs", "cells", "assembly c/s", "assembly s", "solve s", "B/DoF", "Newton"))
for case in ("2d", "3d"):
    s = json.load(open("%s/%s/summary.json" % (out, case)))
    w = s["wall_time_per_phase"]
    print("%-4s %10d %9d %14.0f %12.2f %12.2f %12.0f %8d" % (
        case, s["dofs"], s["cells"], s["assembly_cells_per_second_per_process"],
        w.get("Mechanics: assembly", 0), w.get("Mechanics: linear solve", 0),
        s["memory_per_dof_bytes"], s["newton_iterations"]))
    print("     " + open("%s/%s.time" % (out, case)).read().strip().splitlines()[-1]
          + ", linear iterations %d, steps %d" % (s["linear_iterations"], s["steps"]))
print("targets: assembly >= 300000 cells/s (2D), >= 40000 cells/s (3D) per core; 3D 1M DoFs within 4096 B/DoF")
PY

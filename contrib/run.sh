#!/usr/bin/env bash
# Quick start, command 1: set up, build and run a scene, and draw its figures.
#   contrib/run.sh                 # the seed's scene: frictional heating of two blocks
#   contrib/run.sh [scene.prm] [--set 'Section/Entry=value' ...]
#   ANVIL_NP=2 contrib/run.sh prm/cantilever.prm     # under mpirun with 2 processes
# Figures (the scene's Output/Figure list) go to <output>/figures; pass
# --set 'Output/Figures=false' to skip them.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
seed_scene=false
if [ $# -gt 0 ] && [[ "$1" != --* ]]; then
  scene="$1"
  shift
else
  scene="$ANVIL_ROOT/prm/two_blocks.prm"
  seed_scene=true
fi
runner=()
if [ "${ANVIL_NP:-1}" -gt 1 ]; then
  runner=(mpirun -np "$ANVIL_NP")
fi
# Output/Figures first: the caller's own --set comes later and wins.
if ! $seed_scene; then
  exec "${runner[@]}" "$ANVIL_BUILD/anvil" "$scene" --set 'Output/Figures=true' "$@"
fi

out="output/two_blocks"
"${runner[@]}" "$ANVIL_BUILD/anvil" "$scene" --set 'Output/Figures=true' \
  --set "Output/Directory=$out" "$@"
# The seed's check (Ponthot & Adam, section 4.2, Table 3; prm/two_blocks.prm,
# the scene's header): all the friction work mu p w s = 9.375 N mm/mm becomes
# heat, half in each block; each insulated block ends uniform at its mean
# temperature, dT = (W/2) / (rho c V).
python3 - "$out/summary.json" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
q = s["quantities_of_interest"]
rho_c, W = 2.7e-9 * 0.9e9, 0.2 * 10 * 1.25 * 3.75
balance = {"upper": W / 2 / (rho_c * 1.25 * 1.25), "lower": W / 2 / (rho_c * 5 * 1.25)}
seed = {"upper": (1.231, 1.234), "lower": (0.307, 0.308)}
print("\nFrictional heating of two blocks (the seed: Ponthot & Adam, section 4.2)")
print("  %-10s %10s %16s %14s %14s" % ("", "anvil [K]", "energy bal. [K]", "seed num. [K]",
                                        "seed anal. [K]"))
for b in ("upper", "lower"):
    v = q["delta_T_" + b]
    print("  %-10s %10.4f %16.4f %14.3f %14.3f   (anvil vs balance %+.2f %%)"
          % ("dT_" + b, v, balance[b], seed[b][0], seed[b][1], 100 * (v / balance[b] - 1)))
print("  friction work %.4f N mm/mm (mu p w s = %.4f); %d steps, %d Newton iterations, %.1f s"
      % (q["friction_work"], W, s["steps"], s["newton_iterations"], s["wall_time"]))
PY

#!/usr/bin/env bash
# Benchmark (prints figures, asserts nothing): assembly throughput, linear solve
# time, memory per DoF and Newton iterations for 2D and 3D elastic scenes; the
# assembly's speed-up on 2 threads.
#   contrib/bench.sh            # 2D 512x512 (0.5 M DoFs) and 3D 69^3 (1 M DoFs), one process
#   contrib/bench.sh --small    # quick sizes
#   contrib/bench.sh --perf [--small] [--only heat_plate,...]   # issue 15's figures only (contrib/bench/perf.py)
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
out="${ANVIL_BENCH_DIR:-$ANVIL_BUILD/bench}"
mkdir -p "$out"
if [ "${1:-}" = "--perf" ]; then
  shift
  python3 "$ANVIL_ROOT/contrib/bench/perf.py" "$ANVIL_BUILD" "$out" "$@"
  exit 0
fi
n2=512; n3=69; n3p=40
if [ "${1:-}" = "--small" ]; then n2=128; n3=20; n3p=16; fi
export DEAL_II_NUM_THREADS=1
run() { # name dim blocks [extra --set value | --set pairs...]
  local name=$1 dim=$2 blocks=$3; shift 3
  local extra=()
  while [ $# -gt 0 ]; do
    if [ "$1" = "--set" ]; then extra+=(--set "$2"); shift 2; else extra+=(--set "$1"); shift; fi
  done
  /usr/bin/time -f "%e s wall, %M KB peak" "$ANVIL_BUILD/anvil" "$ANVIL_ROOT/contrib/bench/elastic_block.prm" \
    --set "Dimension=$dim" --set "Geometry/Blocks=$blocks" --set "Output/Directory=$out/$name" \
    "${extra[@]}" 2> "$out/$name.time"
}
J2=(--set "Bodies/body/Material/Model=J2" --set "Bodies/body/Material/Hardening/Initial yield stress=300"
    --set "Bodies/body/Material/Hardening/Hardening modulus=1000")
run 2d 2 "body: 0, 0, 1, 1, $n2, $n2"
run 3d 3 "body: 0, 0, 0, 1, 1, 1, $n3, $n3, $n3" \
  "Boundary conditions/Displacement=front: ux = 0, uy = 0, uz = 0; back: uz = -0.05*t"
# Plastic (J2, F-bar Q1): the return map is in the assembly.
run 2d_plastic 2 "body: 0, 0, 1, 1, $n2, $n2" "Mechanics/Element=F-bar" "${J2[@]}"
run 3d_plastic 3 "body: 0, 0, 0, 1, 1, 1, $n3p, $n3p, $n3p" \
  "Boundary conditions/Displacement=front: ux = 0, uy = 0, uz = 0; back: uz = -0.05*t" "${J2[@]}"
# Newton iterations per step on the necking bar (default tolerances).
"$ANVIL_BUILD/anvil" "$ANVIL_ROOT/prm/necking_bar.prm" --set "Output/Directory=$out/necking" \
  --set "Output/Field interval=0" --set "Output/Verbosity=quiet"
python3 - "$out" <<'PY'
import json, sys
out = sys.argv[1]
print("%-4s %10s %9s %14s %12s %12s %12s %8s" % ("case", "DoFs", "cells", "assembly c/s", "assembly s", "solve s", "B/DoF", "Newton"))
for case in ("2d", "3d", "2d_plastic", "3d_plastic"):
    s = json.load(open("%s/%s/summary.json" % (out, case)))
    w = s["wall_time_per_phase"]
    print("%-4s %10d %9d %14.0f %12.2f %12.2f %12.0f %8d" % (
        case, s["dofs"], s["cells"], s["assembly_cells_per_second_per_process"],
        w.get("Mechanics: assembly", 0), w.get("Mechanics: linear solve", 0),
        s["memory_per_dof_bytes"], s["newton_iterations"]))
    print("     " + open("%s/%s.time" % (out, case)).read().strip().splitlines()[-1]
          + ", linear iterations %d, steps %d" % (s["linear_iterations"], s["steps"]))
    t = s["wall_time_per_phase"]
    print("     time per Newton iteration %.3f s (assembly + solve)" % ((w.get("Mechanics: assembly", 0) + w.get("Mechanics: linear solve", 0)) / max(1, s["newton_iterations"])))
s = json.load(open("%s/necking/summary.json" % out))
print("necking bar (10 x 40 axisymmetric F-bar): %d steps, %.2f Newton iterations per step, %d cut-backs, %.1f s"
      % (s["steps"], s["newton_iterations"] / s["steps"], s["cut_backs"], s["wall_time"]))
print("targets: elastic assembly >= 300000 cells/s (2D), >= 40000 (3D); plastic F-bar >= 150000 (2D), >= 25000 (3D) per core;")
print("         3D 1M DoFs within 4096 B/DoF; <= 6 Newton iterations per step on the necking bar")
PY
"$ANVIL_BUILD/tests/bench_material_points" $([ "${1:-}" = "--small" ] && echo --quick)
# Mechanical assembly on 1 and 2 threads (contrib/bench/assembly_threads.cc):
# time per full assembly (tangent + residual) of a 2D and a 3D J2 F-bar block
# in plastic flow, best of 5, and the speed-up (the rest of this script runs
# on one thread: DEAL_II_NUM_THREADS=1 above).
env -u DEAL_II_NUM_THREADS "$ANVIL_BUILD/tests/bench_assembly_threads" $([ "${1:-}" = "--small" ] && echo --quick)
# Heat assembly (mass, tangent, residual) with 1 and 2 threads, WorkStream
# (contrib/bench/thermal_assembly.cc): a ~20k-DoF 2D and a ~30k-DoF 3D problem,
# best of 5 (--small: 2.5k and 2.2k DoFs, best of 2) and the speed-up. Threads
# allowed here, unlike the one-core figures above.
env -u DEAL_II_NUM_THREADS "$ANVIL_BUILD/tests/bench_thermal_assembly" $([ "${1:-}" = "--small" ] && echo --quick)
# Thermo-mechanical necking bar (prm/necking_bar_thermal.prm, Simo & Miehe 1992)
# per coupling scheme: wall time, cost of the heat half against the mechanics
# (target <= 25 %), ARKode steps, Newton and staggered iterations, temperatures.
# --small: the 5 x 20 mesh instead of 10 x 40.
thermal_sets=(--set "Output/Field interval=0" --set "Output/Verbosity=quiet")
if [ "${1:-}" = "--small" ]; then thermal_sets+=(--set "Geometry/Radial cells=5" --set "Geometry/Axial cells=20"); fi
for scheme in "isothermal split" "adiabatic split" "iterated staggered"; do
  "$ANVIL_BUILD/anvil" "$ANVIL_ROOT/prm/necking_bar_thermal.prm" --set "Physics/Coupling=$scheme" \
    --set "Output/Directory=$out/necking_thermal_${scheme%% *}" "${thermal_sets[@]}" \
    || echo "necking_bar_thermal.prm, $scheme: anvil exited with status $?"
done
python3 - "$out" <<'PY'
import csv, json, os, sys


def bare_rows(path):
    """CSV rows keyed by the column name before its " [unit]"."""
    return [{k.split(" [")[0]: v for k, v in r.items()} for r in csv.DictReader(open(path))]
out = sys.argv[1]
print("thermal necking bar (prm/necking_bar_thermal.prm), one process:")
print("%-19s %6s %5s %7s %13s %10s %9s %10s %9s %9s %9s %8s" % (
    "scheme", "steps", "cuts", "wall s", "heat/mech %", "ARKode/st", "Newton/st", "stagger/st",
    "T max K", "T neck K", "F max kN", "neck mm"))
for scheme in ("isothermal", "adiabatic", "iterated"):
    d = "%s/necking_thermal_%s" % (out, scheme)
    if not os.path.exists(d + "/summary.json"):
        print("%-19s (no summary.json)" % scheme)
        continue
    s = json.load(open(d + "/summary.json"))
    rows = list(bare_rows(d + "/thermal.csv"))
    n = max(1, len(rows))
    col = lambda k: sum(float(r[k]) for r in rows)
    mech, heat = col("mechanics_wall_time"), col("thermal_wall_time")
    F = [float(r["top_Fy"]) for r in bare_rows(d + "/reactions.csv")]
    q = s["quantities_of_interest"]
    stag = "%10.2f" % (col("staggered_iterations") / n) if scheme == "iterated" else "%10s" % "-"
    print("%-19s %6d %5d %7.2f %13.1f %10.2f %9.2f %s %9.1f %9.1f %9.3f %8.4f%s" % (
        s["coupling"], s["steps"], s["cut_backs"], s["wall_time"], 100 * heat / max(mech, 1e-300),
        col("arkode_steps") / n, s["newton_iterations"] / max(1, s["steps"]), stag,
        q["max_temperature"], q["neck_centre_temperature"], max(F) / 1000,
        6.2975 + q["neck_radius_change"], "" if s["status"] == "completed" else "  (" + s["status"] + ")"))
    if scheme == "iterated":
        print("%-19s ARKode steps per heat solve %.2f (1 + staggered iterations heat solves per step)"
              % ("", col("arkode_steps") / (n + col("staggered_iterations"))))
print("columns: heat/mech = sum thermal_wall_time / sum mechanics_wall_time (thermal.csv), target <= 25 %;")
print("         ARKode/st, Newton/st, stagger/st per mechanical step; T max: largest cell-mean temperature;")
print("         T neck: nodal temperature on the axis at mid-length; neck: final neck radius")
PY
# Contact search and evaluation, about 10^4 slave nodes: a strip of 10000 x 2
# cells (10001 slave nodes on its bottom) on a strip of 9999 x 2 cells
# (contrib/bench/contact_strip.prm; --small: 1000 cells).
#  1. contrib/bench/contact_search.cc (build/tests/bench_contact_search), on 1 and 2 processes,
#     times the pieces of ContactProblem (setup, begin_step, couplings,
#     assemble with tangent / residual only) for one-pass and two-pass
#     node-to-segment and for the strip on a rigid plane, outside Newton.
#  2. The whole program on the same scene, one-pass, and on a copy without the
#     Contact section (the upper strip's bottom held instead): Mechanics:
#     assembly / residual per call, the difference being the contact's share
#     in situ (search, elements and their scatter into the matrix), and the
#     setup and wall times.
ncs=10000
if [ "${1:-}" = "--small" ]; then ncs=1000; fi
cs_length=$((ncs / 100))   # square cells of 0.01 mm
cs_scene="$ANVIL_ROOT/contrib/bench/contact_strip.prm"
cs_sets=(--set "Geometry/Blocks=lower: 0, 0, $cs_length, 0.02, $((ncs - 1)), 2; upper: 0, 0.02, $cs_length, 0.04, $ncs, 2")
cs_bin="$ANVIL_BUILD/tests/bench_contact_search"
if [ -x "$cs_bin" ]; then
  for np in 1 2; do
    for variant in "" "Contact/strip/Two-pass=true" "Contact/strip/Master=floor"; do
      extra=()
      [ -n "$variant" ] && extra=(--set "$variant")
      echo "contact_search, $np process(es), ${variant:-one-pass}:"
      OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 mpirun --oversubscribe -np $np \
        "$cs_bin" "$cs_scene" "${cs_sets[@]}" "${extra[@]}" \
        || echo "contact_search ${variant:-one-pass} (np $np): exited with status $?"
    done
  done
else
  echo "contact_search: $cs_bin is missing (built with the tests: cmake --build $ANVIL_BUILD)"
fi
sed '/^subsection Contact/,/^end/d' "$cs_scene" > "$out/contact_strip_without_contact.prm"
"$ANVIL_BUILD/anvil" "$cs_scene" "${cs_sets[@]}" --set "Output/Directory=$out/contact_strip" \
  --set "Output/Verbosity=normal" \
  --set "Boundary conditions/Displacement=lower.bottom: ux = 0, uy = 0; upper.left: ux = 0" \
  > "$out/contact_strip.log" 2>&1 || echo "contact_strip.prm: anvil exited with status $?"
"$ANVIL_BUILD/anvil" "$out/contact_strip_without_contact.prm" "${cs_sets[@]}" \
  --set "Output/Directory=$out/contact_strip_without_contact" --set "Output/Verbosity=normal" \
  --set "Boundary conditions/Displacement=lower.bottom: ux = 0, uy = 0; upper.bottom: ux = 0, uy = 0" \
  > "$out/contact_strip_without_contact.log" 2>&1 || echo "contact_strip (without contact): anvil exited with status $?"
python3 - "$out" <<'PY'
import json, os, re, sys
out = sys.argv[1]
def timers(case):
    """Per section (calls, seconds) from the timer table at the end of the log."""
    t = {}
    for line in open("%s/%s.log" % (out, case)):
        m = re.match(r"\|\s*(.+?)\s*\|\s*(\d+)\s*\|\s*([0-9.e+-]+)s\s*\|", line)
        if m:
            t[m.group(1)] = (int(m.group(2)), float(m.group(3)))
    return t
cases = ("contact_strip", "contact_strip_without_contact")
if not all(os.path.exists("%s/%s/summary.json" % (out, c)) for c in cases):
    print("contact strip, whole program: a run failed (see %s/contact_strip*.log)" % out)
    sys.exit(0)
s = {c: json.load(open("%s/%s/summary.json" % (out, c))) for c in cases}
t = {c: timers(c) for c in cases}
print("contact strip, whole program, one process (%d cells, %d DoFs):" % (s[cases[0]]["cells"], s[cases[0]]["dofs"]))
print("  %-28s %14s %14s %14s" % ("s per call", "with contact", "without", "contact share"))
for sec in ("Mechanics: assembly", "Mechanics: residual"):
    a, b = t[cases[0]].get(sec), t[cases[1]].get(sec)
    if a and b:
        pa, pb = a[1] / a[0], b[1] / b[0]
        print("  %-28s %14.4f %14.4f %14.4f" % (sec, pa, pb, pa - pb))
for sec in ("Mechanics: setup",):
    a, b = t[cases[0]].get(sec), t[cases[1]].get(sec)
    if a and b:
        print("  %-28s %14.4f %14.4f %14.4f" % (sec + " (s)", a[1], b[1], a[1] - b[1]))
outside = {c: s[c]["wall_time"] - sum(v[1] for v in t[c].values()) for c in cases}
print("  %-28s %14.4f %14.4f %14.4f" % ("outside the timers (s)", outside[cases[0]], outside[cases[1]],
                                        outside[cases[0]] - outside[cases[1]]))
print("  %-28s %14.4f %14.4f" % ("wall time (s)", s[cases[0]]["wall_time"], s[cases[1]]["wall_time"]))
print("  steps %d / %d, Newton iterations %d / %d" % (s[cases[0]]["steps"], s[cases[1]]["steps"],
      s[cases[0]]["newton_iterations"], s[cases[1]]["newton_iterations"]))
print("  (begin_step, the tributary areas and the candidate search of each step, runs outside the timers)")
PY
# The coupling schemes side by side (issue 11, contrib/bench/monolithic.py): per
# scheme (isothermal, adiabatic, iterated staggered, monolithic) on the thermal
# necking bar and the two-block scene, wall time, steps, Newton and linear
# iterations, and the error against the tightest monolithic run.
ANVIL_EXECUTABLE="$ANVIL_BUILD/anvil" ANVIL_BENCH_DIR="$out" python3 "$ANVIL_ROOT/contrib/bench/monolithic.py" \
  $([ "${1:-}" = "--small" ] && echo --small) || echo "contrib/bench/monolithic.py failed"
# The seed's two-block scene (prm/two_blocks.prm): wall time on one core
# (target <= 2 s against the seed's 18.33 s of 2002), steps, Newton iterations.
"$ANVIL_BUILD/anvil" "$ANVIL_ROOT/prm/two_blocks.prm" --set "Output/Directory=$out/two_blocks" \
  --set "Output/Field interval=0" --set "Output/Verbosity=quiet" || echo "two_blocks.prm: anvil exited with status $?"
python3 - "$out" <<'PY'
import json, sys
s = json.load(open(sys.argv[1] + "/two_blocks/summary.json"))
q = s["quantities_of_interest"]
print("two blocks (prm/two_blocks.prm), one process: %.2f s wall (seed 18.33 s), %d steps (seed 77), "
      "%d Newton iterations (seed 217), %.2f per step, ARKode %.2f steps per step; dT %.4f / %.4f K "
      "(analytic 1.2346 / 0.3086)" % (s["wall_time"], s["steps"], s["newton_iterations"],
                                      s["newton_iterations"] / s["steps"], s["heat"]["arkode_steps_per_step"],
                                      q["delta_T_upper"], q["delta_T_lower"]))
PY
# The seed's tube impact, case 3 (prm/tube_impact.prm, issue 12): wall time on
# one core and on two processes, steps, cut-backs, Newton iterations, the
# phases (contact search and evaluation run inside Mechanics: assembly and
# residual), beside the seed's 199 steps / 755 iterations / 251 s (target
# <= 10 s on one core). --small: the first 0.5 ms only.
tube_sets=(--set "Output/Field interval=0" --set "Output/Verbosity=quiet")
if [ "${1:-}" = "--small" ]; then tube_sets+=(--set "Time/End time=5e-4"); fi
"$ANVIL_BUILD/anvil" "$ANVIL_ROOT/prm/tube_impact.prm" --set "Output/Directory=$out/tube_np1" "${tube_sets[@]}" \
  || echo "tube_impact.prm: anvil exited with status $?"
mpirun -np 2 --oversubscribe "$ANVIL_BUILD/anvil" "$ANVIL_ROOT/prm/tube_impact.prm" \
  --set "Output/Directory=$out/tube_np2" "${tube_sets[@]}" || echo "tube_impact.prm, np = 2: anvil exited with status $?"
python3 - "$out" <<'PY'
import csv, json, os, sys


def bare_rows(path):
    """CSV rows keyed by the column name before its " [unit]"."""
    return [{k.split(" [")[0]: v for k, v in r.items()} for r in csv.DictReader(open(path))]
out = sys.argv[1]
for np in (1, 2):
    d = "%s/tube_np%d" % (out, np)
    if not os.path.exists(d + "/summary.json"):
        print("tube impact np = %d: no summary.json" % np)
        continue
    s = json.load(open(d + "/summary.json"))
    w = s["wall_time_per_phase"]
    rows = list(bare_rows(d + "/reactions.csv"))
    t = [float(r["time"]) for r in rows]
    F = [-float(r["top_Fy"]) for r in rows]
    W = sum(0.5 * (F[i] + F[i - 1]) * (t[i] - t[i - 1]) for i in range(1, len(t)))
    print("tube impact case 3 (prm/tube_impact.prm), np = %d: %.1f s wall (seed 251 s, target <= 10 s), %d steps "
          "(seed 199), %d cut-backs, %d Newton iterations (seed 556 + 199 thermal), mean drive force %.2f kN; "
          "assembly %.1f s, residual %.1f s (both with the contact search and evaluation), linear solve %.1f s; "
          "energy balance %.2g" % (np, s["wall_time"], s["steps"], s["cut_backs"], s["newton_iterations"],
                                   W / t[-1] / 1000, w.get("Mechanics: assembly", 0), w.get("Mechanics: residual", 0),
                                   w.get("Mechanics: linear solve", 0), s["energy"]["balance_error"]))
PY
# The parts refactor (issue 10): every shipped scene before and after, and the
# run time of the regression layer (tests/regression.py, ctest -L regression).
python3 "$ANVIL_ROOT/contrib/bench/compare_walltimes.py" "$ANVIL_BUILD"
start=$(date +%s.%N)
(cd "$ANVIL_BUILD" && ctest -L regression -j2 > "$out/regression.log" 2>&1) || echo "regression layer: FAILED (see $out/regression.log)"
echo "regression layer: $(grep -c 'Passed' "$out/regression.log") cases, $(python3 -c "import sys; print(round(float(sys.argv[2]) - float(sys.argv[1]), 1))" "$start" "$(date +%s.%N)") s wall on ctest -j2"
# Issue 15, solvers that scale (contrib/bench/solver_scaling.py): Krylov
# iterations per solve and time per Newton iteration against DoFs, GMRES + AMG
# (rigid-body modes) and KLU, plastic F-bar 2D and 3D and the contact strip;
# the fitted exponents and the crossover ('Direct solver limit = measured').
python3 "$ANVIL_ROOT/contrib/bench/solver_scaling.py" "$ANVIL_BUILD" "$out/solver_scaling" \
  $([ "${1:-}" = "--small" ] && echo --small) || echo "contrib/bench/solver_scaling.py failed"
# np = 1 against np = 2 on the largest 3D plastic block and contact strip just
# run (issue 15, >= 1.7): the same cases on two processes, the strip cut per
# body so that its contact surface is shared, the cube both ways;
# contrib/bench/speedup.py pairs them.
if [ "${1:-}" = "--small" ]; then large_sizes="3d:10;strip:1000"; else large_sizes="3d:30;strip:16000"; fi
OMPI_MCA_mpi_yield_when_idle=1 python3 "$ANVIL_ROOT/contrib/bench/solver_scaling.py" "$ANVIL_BUILD" \
  "$out/solver_scaling" --cases 3d --solvers iterative --sizes "$large_sizes" --np 2 \
  || echo "contrib/bench/solver_scaling.py --np 2 (3d) failed"
# The cube cut in two slabs (one plane) instead of p4est's staircase: ML
# aggregates within a process, and the plane leaves np 1's aggregates
# (doc/linear_solver.md, session 20).
OMPI_MCA_mpi_yield_when_idle=1 python3 "$ANVIL_ROOT/contrib/bench/solver_scaling.py" "$ANVIL_BUILD" \
  "$out/solver_scaling" --cases 3d --solvers iterative --sizes "$large_sizes" --np 2 --partition "per body" \
  || echo "contrib/bench/solver_scaling.py --np 2 --partition 'per body' (3d) failed"
OMPI_MCA_mpi_yield_when_idle=1 python3 "$ANVIL_ROOT/contrib/bench/solver_scaling.py" "$ANVIL_BUILD" \
  "$out/solver_scaling" --cases strip --solvers iterative --sizes "$large_sizes" --np 2 --partition "per body" \
  || echo "contrib/bench/solver_scaling.py --np 2 (strip) failed"
python3 "$ANVIL_ROOT/contrib/bench/speedup.py" "$out/solver_scaling/results.json" || echo "contrib/bench/speedup.py failed"
# Issue 15 (performance): solver and process wall time, thermal share, time per
# Newton iteration against one assembly + one solve, Krylov iterations per
# solve on the two blocks, the thermal necking bar and the tube (case 3); the
# linear heat benchmark contrib/bench/heat_plate.prm.
python3 "$ANVIL_ROOT/contrib/bench/perf.py" "$ANVIL_BUILD" "$out" $([ "${1:-}" = "--small" ] && echo --small)

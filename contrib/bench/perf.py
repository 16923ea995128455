"""Issue 15's figures (performance), printed, never asserted (contrib/bench.sh --perf).

Per shipped scene with mechanics (prm/*.prm), one process, one thread:
  - solver wall time (summary.json wall_time) and the whole process (start-up,
    reading, writing included) measured around it; the start-up alone
    (`anvil SCENE --check`);
  - thermal share: sum of thermal_wall_time / sum of mechanics_wall_time
    (thermal.csv), target <= 25 %;
  - time per Newton iteration (mechanics' wall time / Newton iterations) against
    one assembly + one linear solve (their timer sections per call), and the
    ratio, target <= 1.5; the mechanics' wall time is thermal.csv's
    mechanics_wall_time in a heat scene, else summary.json's step_loop_wall_time
    (every step's work, failed attempts, commit, newton.csv and the step line
    included; outputs, checkpoints, the set-up before the first step and the
    closing after the last left out); "(old)" the definition of sessions <= 23
    (the solver's time less mesh, 'Mechanics: setup', outputs and checkpoints,
    which counted the rest of the set-up and the closing per Newton iteration);
  - the same ratio in CPU seconds (summary.json cpu_time_per_phase), which a
    loaded machine does not inflate: the 'Mechanics: Newton solve' section
    (everything of solve_step: contact step, pattern, predictor, iterations,
    line search; not commit, output or heat) per Newton iteration against the
    CPU per call of assembly + linear solve; the same for the step loop's
    step_loop_cpu_time (cpu steps, heat-less scenes: the CPU figure of the
    wall ratio);
    beside them the share of that Newton cost spent in residual-only
    evaluations ('Mechanics: residual');
    (contrib/bench/instruction_ratio.py: the same ratios in instructions);
  - Krylov iterations per mechanical linear solve;
and the thermal-only benchmark contrib/bench/heat_plate.prm (15 625 temperature
unknowns, linear): wall time, ARKode steps, nonlinear iterations, linear solves.

    python3 contrib/bench/perf.py BUILD_DIR OUT_DIR [--small] [--only NAME[,NAME...]]

--only runs the named cases alone (two_blocks, necking_bar_thermal, tube_case3,
heat_plate, or any other shipped scene by its file name without .prm), e.g. to
repeat one timing on a loaded machine.
"""
import csv
import json
import os
import re
import resource
import subprocess
import sys
import time

build, out = sys.argv[1], sys.argv[2]
small = "--small" in sys.argv[3:]
only = None
if "--only" in sys.argv[3:-1]:
    only = set(sys.argv[sys.argv.index("--only") + 1].split(","))
wanted = lambda name: only is None or name in only
os.makedirs(out, exist_ok=True)
root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
anvil = os.path.join(build, "anvil")
env = dict(os.environ, DEAL_II_NUM_THREADS="1")


def bare_rows(path):
    """CSV rows keyed by the column name before its " [unit]"."""
    if not os.path.exists(path):
        return []
    return [{k.split(" [")[0]: v for k, v in r.items()} for r in csv.DictReader(open(path))]


def timers(log):
    """Per timer section (calls, seconds) from the table at the end of a log."""
    t = {}
    for line in open(log):
        m = re.match(r"\|\s*(.+?)\s*\|\s*(\d+)\s*\|\s*([0-9.e+-]+)s\s*\|", line)
        if m:
            t[m.group(1)] = (int(m.group(2)), float(m.group(3)))
    return t


def run(name, scene, sets=()):
    """Run a scene (Verbosity normal: the timer table), return (summary, timers, process s)."""
    d = os.path.join(out, "perf_" + name)
    cmd = [anvil, os.path.join(root, scene), "--threads", "1", "--set", "Output/Directory=" + d,
           "--set", "Output/Field interval=0", "--set", "Output/Verbosity=normal"]
    for s in sets:
        cmd += ["--set", s]
    start, cpu = time.time(), cpu_seconds()
    with open(d + ".log", "w") as log:
        status = subprocess.call(cmd, stdout=log, stderr=subprocess.STDOUT, env=env)
    process = (time.time() - start, cpu_seconds() - cpu)
    if status != 0 or not os.path.exists(d + "/summary.json"):
        print("%-22s anvil exited with status %d (see %s.log)" % (name, status, d))
        return None, None, None
    return json.load(open(d + "/summary.json")), timers(d + ".log"), process


def cpu_seconds():
    """User + system CPU seconds of the finished children (a loaded machine's wall clock lies)."""
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def startup(scene):
    """Seconds of `anvil SCENE --check` (load, parse, mesh; no solve), best of 3."""
    best = 1e300
    for _ in range(3):
        start = time.time()
        subprocess.call([anvil, os.path.join(root, scene), "--check"], stdout=subprocess.DEVNULL,
                        stderr=subprocess.DEVNULL, env=env)
        best = min(best, time.time() - start)
    return best


def per_call(t, section):
    c = t.get(section)
    return c[1] / c[0] if c and c[0] else 0.


tube_sets = ["Time/End time=5e-4"] if small else []
cases = [("two_blocks", "prm/two_blocks.prm", []),
         ("necking_bar_thermal", "prm/necking_bar_thermal.prm", []),
         ("tube_case3", "prm/tube_impact.prm", tube_sets)]
# The "ratio on every shipped scene": the other scenes with mechanics
# (steady_slab and heat_half_space are heat only: the heat plate below).
cases += [(os.path.splitext(f)[0], "prm/" + f, [])
          for f in sorted(os.listdir(os.path.join(root, "prm")))
          if f.endswith(".prm") and os.path.splitext(f)[0] not in
          ("two_blocks", "necking_bar_thermal", "tube_impact", "steady_slab", "heat_half_space")]
print("issue 15 figures, one process, one thread%s:" % (" (--small: tube to 0.5 ms)" if small else ""))
print("%-20s %7s %13s %8s %6s %7s %8s %9s %10s %6s %6s %9s %9s %6s %8s %6s" % (
    "scene", "solver", "process (cpu)", "start-up", "steps", "Newton", "heat/mech", "s/Newton",
    "asm+solve", "ratio", "(old)", "cpu ratio", "cpu steps", "resid", "Krylov/sol", "arkode"))
for name, scene, sets in cases:
    if not wanted(name):
        continue
    s, t, process = run(name, scene, sets)
    if s is None:
        continue
    rows = bare_rows(os.path.join(out, "perf_" + name, "thermal.csv"))
    mech = sum(float(r["mechanics_wall_time"]) for r in rows)
    heat = sum(float(r["thermal_wall_time"]) for r in rows)
    arkode = sum(float(r["arkode_steps"]) for r in rows) / max(1, len(rows))
    w = s["wall_time_per_phase"]
    c = s.get("cpu_time_per_phase", {})
    old_mech = mech
    cpu_steps = None
    if not rows:
        # No heat: the mechanics is the solver's time less what is paid once
        # per run or per output (mesh, set-up, fields, checkpoints), as the
        # split scenes' mechanics_wall_time leaves them out too: summary.json's
        # step_loop_wall_time, the step loop without outputs and checkpoints. Before it
        # existed (sessions ≤ 23, "(old)"): the solver's time less the mesh,
        # 'Mechanics: setup', outputs and checkpoints, which left the rest of
        # the set-up before the first step (probes located, histories opened,
        # the problem's construction) and the closing after the last step in.
        old_mech = s["wall_time"] - sum(w.get(k, 0.0) for k in
                                        ("Mesh", "Mechanics: setup", "Output", "Checkpoint"))
        mech = s.get("step_loop_wall_time", old_mech)
        cpu_steps = s.get("step_loop_cpu_time")
    newton = max(1, s["newton_iterations"])
    one = per_call(t, "Mechanics: assembly") + per_call(t, "Mechanics: linear solve")
    solves = t.get("Mechanics: linear solve", (0, 0))[0]
    # The CPU ratio: section CPU seconds of the same run, calls from the timer table.
    cpu_call = lambda k: c.get(k, 0.) / max(1, t.get(k, (0, 0))[0])
    cpu_one = cpu_call("Mechanics: assembly") + cpu_call("Mechanics: linear solve")
    cpu_newton = c.get("Mechanics: Newton solve", 0.) / newton
    print("%-20s %7.2f %6.2f (%4.2f) %8.2f %6d %7d %8.1f%% %9.4f %10.4f %6.2f %6.2f %9.2f %9s %5.0f%% %8.1f %6.2f" % (
        name, s["wall_time"], process[0], process[1], startup(scene), s["steps"], s["newton_iterations"],
        100 * heat / max(mech, 1e-300), mech / newton, one, mech / newton / max(one, 1e-300),
        old_mech / newton / max(one, 1e-300), cpu_newton / max(cpu_one, 1e-300),
        "-" if cpu_steps is None else "%.2f" % (cpu_steps / newton / max(cpu_one, 1e-300)),
        100 * c.get("Mechanics: residual", 0.) / max(newton * cpu_newton, 1e-300),
        s["linear_iterations"] / max(1, solves), arkode))
print("  solver: summary.json wall_time (two blocks: target <= 0.5 s, seed 18.33 s); process: the whole run, "
      "wall (CPU seconds) (target <= 1 s); start-up: anvil --check (best of 3)")
print("  load average now %.1f on %d cores: wall times are only comparable on an idle machine"
      % (os.getloadavg()[0], os.cpu_count()))
print("  heat/mech: thermal.csv thermal / mechanics wall time (target <= 25 %); s/Newton: mechanics wall time per "
      "Newton iteration (heat scenes: thermal.csv's mechanics_wall_time; the others: summary.json's step_loop_wall_time, "
      "the step loop without set-up, outputs and checkpoints); asm+solve: one 'Mechanics: assembly' + one "
      "'Mechanics: linear solve' (timer means); ratio: s/Newton / asm+solve (target <= 1.5); (old): the same with "
      "the definition of sessions <= 23 (solver time - mesh, 'Mechanics: setup', outputs, checkpoints: the rest of "
      "the set-up and the run's closing counted per Newton iteration)")
print("  cpu ratio: CPU seconds of 'Mechanics: Newton solve' per Newton iteration / CPU per assembly + linear solve "
      "(load-independent; no commit, output or heat); cpu steps: the same for step_loop_cpu_time (user + system), commit, "
      "newton.csv and the step line included (heat-less scenes); resid: the Newton CPU's share in residual-only "
      "evaluations")
print("  Krylov/sol: mechanical linear iterations per linear solve (1: direct); arkode: ARKode steps per step")

# The heat problem alone: 124 x 124 Q1 cells, a boundary temperature jump and
# convection, linear (contrib/bench/heat_plate.prm).
plate_sets = ["Time/End time=5"] if small else []
s, t, process = run("heat_plate", "contrib/bench/heat_plate.prm", plate_sets) if wanted("heat_plate") else (None,) * 3
if s is not None:
    h = s.get("heat", {})
    rows = bare_rows(os.path.join(out, "perf_heat_plate", "thermal.csv"))
    col = lambda k: sum(float(r[k]) for r in rows if k in r)
    print("heat plate (contrib/bench/heat_plate.prm%s), %d temperature unknowns: %.2f s solver, %.2f s process "
          "(%.2f s CPU); %d steps, ARKode steps %d, nonlinear iterations %d, linear setups %d, linear solves %d "
          "(%d Krylov and mass CG iterations); "
          "Heat: residual %d calls %.2f s, tangent %d calls %.2f s, Newton matrix %d calls %.2f s; "
          "T_mean %.6f K, T_p1 %.6f K" % (
              ", to 5 s" if small else "", s.get("temperature_dofs", 0), s["wall_time"], process[0], process[1], s["steps"],
              col("arkode_steps"), col("nonlinear_iterations"), col("linear_setups"), col("linear_solves"), col("linear_iterations"),
              t.get("Heat: residual", (0, 0))[0] + t.get("Heat: residual (linear)", (0, 0))[0],
              t.get("Heat: residual", (0, 0))[1] + t.get("Heat: residual (linear)", (0, 0))[1],
              t.get("Heat: tangent", (0, 0))[0], t.get("Heat: tangent", (0, 0))[1],
              t.get("Heat: Newton matrix", (0, 0))[0], t.get("Heat: Newton matrix", (0, 0))[1],
              s["quantities_of_interest"]["T_mean"], s["quantities_of_interest"]["T_p1"]))

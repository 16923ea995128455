"""The step loop's clock holds the steps' work and nothing paid per output or per run.

contrib/bench/perf.py sets summary.json's step_loop_wall_time and
step_loop_cpu_time (simulator.cc) per Newton iteration against one assembly and one linear solve: it must contain
the Newton solves and must not contain the fields, checkpoints, mesh or set-up.
Checked on the thick cylinder with a field and a checkpoint at every step, so
that outputs and checkpoints are a large share of the run, by two properties
of intervals on one clock, whatever the machine's load:
  - nested: the Newton solve section lies inside the step loop, so its CPU
    seconds cannot exceed the step loop's;
  - disjoint: the step loop, the mesh, 'Mechanics: setup', the outputs and the
    checkpoints do not overlap, so their wall times sum to at most the run's
    (summary.json wall_time). Were the outputs and checkpoints inside the step
    loop's clock they would count twice, and the sum would exceed the run
    by more than the untimed set-up.
"""
from anvil_test import run, check, finish

out, s, _ = run("prm/thick_cylinder.prm", ["Output/Field interval=1", "Output/Checkpoint interval=1",
                                          "Output/Verbosity=normal"], name="step_timer")
w, c = s["wall_time_per_phase"], s["cpu_time_per_phase"]
check("step_loop_wall_time" in s and "step_loop_cpu_time" in s, "summary.json has the step loop's times")
loop_cpu, loop_wall = s.get("step_loop_cpu_time", 0.), s.get("step_loop_wall_time", 0.)
newton = c.get("Mechanics: Newton solve", 0.)
# (1e-5 s: the two clocks' rounding to microseconds at each end)
check(newton > 0 and loop_cpu >= newton - 1e-5,
      "CPU: step loop %.4f s >= the Newton solves inside it %.4f s" % (loop_cpu, newton))
parts = ["Mesh", "Mechanics: setup", "Output", "Checkpoint"]
total = loop_wall + sum(w.get(k, 0.) for k in parts)
check(w.get("Output", 0.) > 0 and w.get("Checkpoint", 0.) > 0, "outputs and checkpoints were timed")
check(total <= s["wall_time"] + 1e-3,
      "wall: the step loop + %s sum to %.4f s <= the run's %.4f s" % (" + ".join(parts), total, s["wall_time"]))
finish()

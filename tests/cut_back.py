"""Adaptive time stepping: the necking bar (prm/necking_bar.prm) with a first
step of half the whole stroke (3.5 mm) cannot converge; the stepper cuts the
step back (states reverted, material points included), grows it again after
easy steps, and ends with the answer of the run with small steps (0.14 mm):
final neck radius and end force within 1 %."""
from anvil_test import run, check, close, finish

_, big, _ = run("prm/necking_bar.prm", ["Time/Time step=0.5", "Output/Field interval=0", "Output/Verbosity=quiet"],
                name="cut_back_large")
_, small, _ = run("prm/necking_bar.prm", ["Time/Time step=0.02", "Output/Field interval=0", "Output/Verbosity=quiet"],
                  name="cut_back_small")
print("  first step 0.5: %d steps, %d cut-backs, %d Newton iterations; steps of 0.02: %d steps, %d iterations"
      % (big["steps"], big["cut_backs"], big["newton_iterations"], small["steps"], small["newton_iterations"]))
check(big["cut_backs"] > 0, "the too-large first step was cut back (%d times)" % big["cut_backs"])
check(big["status"] == "completed", "the run completed after cutting back")
a, b = big["quantities_of_interest"], small["quantities_of_interest"]
close(a["neck_radius_change"], b["neck_radius_change"], 1e-2, "neck radius change (mm) against small steps")
close(a["final_force"], b["final_force"], 1e-2, "end force (N) against small steps")
finish()

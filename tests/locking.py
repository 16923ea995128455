"""Volumetric locking in isochoric plastic flow: Prandtl's flat punch in plane
strain (prm/punch.prm, elastic-perfectly plastic von Mises), punch force at
0.05 mm of indentation. Reference: Q2 on the once-refined mesh. Standard Q1
locks (too stiff, and slow to converge under refinement); F-bar Q1 converges
to the reference. For orientation the small-strain limit (2 + pi) k is printed
(the force at 0.05 mm is above it: the elastic-plastic transition and the
change of geometry)."""
import math
from anvil_test import run, check, finish

def force(name, sets):
    _, s, _ = run("prm/punch.prm", sets + ["Output/Field interval=0", "Output/Verbosity=quiet"], name="locking_" + name)
    return -s["quantities_of_interest"]["punch_force"], s

ref, s_ref = force("q2_ref1", ["Mechanics/Element=standard", "Mechanics/Polynomial degree=2",
                               "Geometry/Global refinements=1"])
results = {}
for el in ("F-bar", "standard"):
    for r in (0, 1):
        results[(el, r)] = force("%s_ref%d" % (el.replace("-", ""), r),
                                 ["Mechanics/Element=" + el, "Geometry/Global refinements=%d" % r])[0]
print("  element          mesh   punch force (N/mm)   error vs Q2 reference")
for (el, r), f in results.items():
    print("  Q1 %-12s  ref %d   %10.2f           %+.2f %%" % (el, r, f, 100 * (f - ref) / ref))
print("  Q2 (reference)   ref 1   %10.2f   (Prandtl limit (2 + pi) k = %.2f)" % (ref, (2 + math.pi) * 300 / math.sqrt(3)))
err = {k: abs(v - ref) / ref for k, v in results.items()}
check(err[("F-bar", 1)] < 0.01, "F-bar Q1 on the refined mesh within 1 %% of the Q2 reference (%.2f %%)" % (100 * err[("F-bar", 1)]))
check(err[("standard", 1)] > 0.05, "standard Q1 locks: %.1f %% too stiff on the refined mesh" % (100 * err[("standard", 1)]))
check(err[("F-bar", 0)] < 0.5 * err[("standard", 0)], "F-bar error below half the standard Q1 error on the coarse mesh")
check(err[("F-bar", 1)] < err[("F-bar", 0)] / 4, "F-bar converges under refinement (error %.2f %% -> %.2f %%)"
      % (100 * err[("F-bar", 0)], 100 * err[("F-bar", 1)]))
finish()

"""Three levels of geometric coarse spaces (ANVIL_GMG_LEVELS=3; source/mechanics/
coarse_space_levels.cc, multilevel_cycle.cc, galerkin_product.cc): Chebyshev on
the fine and the middle level, ML on the coarsest. GMRES reaches the direct
solver's (KLU) answer, every reaction and energy column to 1e-6 of its scale,
on the box path (the 3D plastic F-bar block of 8^3 cells: 4^3 and 2^3 below)
and on the hierarchy path (two J2 bodies with a gap, blocks refined twice, 2D
and 3D: the grandparents' vertices); two processes give np 1's answer (p4est's
partition, and per body on the hierarchy path). The log names three levels."""
import os

from anvil_test import run, check, finish, largest_column_difference
from geometric_scenes import DIRECT, GEOMETRIC, PER_BODY, BLOCK, TWICE, THREE_D

os.environ["ANVIL_GMG_LEVELS"] = "3"
os.environ["ANVIL_GMG_LOG"] = "1"
for label, scene, sets, runs in [
        ("box", "contrib/bench/elastic_block.prm", BLOCK,
         [("direct", DIRECT, 1), ("geometric", GEOMETRIC, 1), ("np2", GEOMETRIC, 2)]),
        ("2D hierarchy", "tests/geometric_two_bodies.prm", TWICE,
         [("direct", DIRECT, 1), ("geometric", [], 1), ("np2", [], 2), ("np2_per_body", PER_BODY, 2)]),
        ("3D hierarchy", "tests/geometric_two_bodies.prm", TWICE + THREE_D,
         [("direct", DIRECT, 1), ("geometric", [], 1), ("np2", [], 2), ("np2_per_body", PER_BODY, 2)])]:
    out, per_solve = {}, {}
    for name, extra, np in runs:
        out[name], s, stdout = run(scene, sets + extra, np=np,
                                   name="geometric_three_levels_%s_%s" % (label.replace(" ", "_"), name))
        check(s["status"] == "completed", "%s %s: completed" % (label, name))
        per_solve[name] = s["linear_iterations"] / max(1, s["newton_iterations"])
        if name != "direct":
            check("geometric coarse space: 3 levels" in stdout, "%s %s: the log names three levels" % (label, name))
    check(per_solve["geometric"] > 1, "%s: %.1f Krylov iterations per solve" % (label, per_solve["geometric"]))
    for a, b in [("direct", "geometric")] + [("geometric", n) for n, _, np in runs if np == 2]:
        worst, where = largest_column_difference(out[a], out[b], ("reactions.csv", "energy.csv"))
        check(worst <= 1e-6, "%s %s vs %s: largest difference %.1e of its column's scale (%s) <= 1e-6"
              % (label, a, b, worst, where))
finish()

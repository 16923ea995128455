"""The coarsest level's solve of the geometric multilevel cycle (multilevel_cycle.cc,
geometric_coarse_space.cc), three levels (ANVIL_GMG_LEVELS=3): ML's V-cycle repeated
on A_2's residual (ANVIL_GMG_COARSE_CYCLES=3, the kept vectors) and A_2 factored by KLU
(ANVIL_GMG_COARSE_DIRECT=1, the factorisation kept across solves). Either way GMRES
reaches the direct solver's (KLU on K) answer, every reaction and energy column to
1e-6 of its scale, on the box path (the 3D plastic F-bar block of 8^3 cells) and on
the hierarchy path (two J2 bodies with a gap, blocks refined twice, 3D), and two
processes give one process's answer (p4est's partition, and per body on the
hierarchy path). On the box ML aggregates A_2 (coarse: max size 30) so that its
V-cycle is inexact; KLU on A_2 is an exact coarse solve, so its cycle needs no more Krylov
iterations than one ML V-cycle's.

The automatic rule (geometric_coarse_space.cc, coarsest_ml_cycles()): a coarsest
level the mesh cannot coarsen although it has >= 14 000 rows gets two ML cycles
(three below a cycle whose fine level has >= 32 times its rows: 1 M DoFs).
2D boxes (elastic, geometric asked for): 170^2 cells halve to 85 (odd), a coarsest
of 86^2 nodes x 2 = 14 792 rows under 58 482: two; 172^2 halve to 86 and 43, 15 138
rows are coarsened again to 44^2 x 2 = 3 872, which keeps one. The log names the choice."""
import os

from anvil_test import run, check, finish, largest_column_difference
from geometric_scenes import DIRECT, GEOMETRIC, PER_BODY, BLOCK, TWICE, THREE_D

os.environ["ANVIL_GMG_LOG"] = "1"
TWICE_3D = TWICE + THREE_D
# A_2 is small (81 rows on the box): ML would factor it whole; 'coarse: max size'
# 30 makes its V-cycle an inexact solve, as on a large coarsest level.
ML = "coarse: max size:int=30"
VARIANTS = {"ml3": {"ANVIL_GMG_COARSE_CYCLES": "3", "ANVIL_ML_PARAMETERS": ML},
            "klu": {"ANVIL_GMG_COARSE_DIRECT": "1"},
            "ml1": {"ANVIL_GMG_COARSE_CYCLES": "1", "ANVIL_ML_PARAMETERS": ML}}
LOGGED = {"ml3": "coarsest: ML x3", "klu": "coarsest: KLU", "ml1": "coarsest: ML x1"}


def run_variant(variant, scene, sets, np, name, aggregate):
    """One run with the variant's environment (the others' removed)."""
    os.environ["ANVIL_GMG_LEVELS"] = "3"
    for env in VARIANTS.values():
        for key in env:
            os.environ.pop(key, None)
    os.environ.update(VARIANTS.get(variant, {}))
    if not aggregate:
        os.environ.pop("ANVIL_ML_PARAMETERS", None)
    return run(scene, sets, np=np, name=name)


# The hierarchy path numbers the coarse dofs in the order of their fine dofs: on
# two processes ML's aggregation of A_2 refuses its ghost columns' node blocks
# ("deficient ghost block"), so there ML factors A_2 whole (ML x3 repeats an
# exact solve) and only the box path compares an inexact ML with KLU.
for label, scene, sets, aggregate, runs in [
        ("box", "contrib/bench/elastic_block.prm", BLOCK + GEOMETRIC, True,
         [("ml1", [], 1), ("ml3", [], 1), ("ml3", [], 2), ("klu", [], 1), ("klu", [], 2)]),
        ("3D hierarchy", "tests/geometric_two_bodies.prm", TWICE_3D, False,
         [("ml1", [], 1), ("ml3", [], 1), ("ml3", [], 2), ("ml3", PER_BODY, 2),
          ("klu", [], 1), ("klu", [], 2), ("klu", PER_BODY, 2)])]:
    key = label.replace(" ", "_")
    direct, _, _ = run_variant("none", scene, sets + DIRECT, 1, "geometric_coarsest_%s_direct" % key, False)
    out, per_solve = {}, {}
    for variant, extra, np in runs:
        name = "%s_np%d%s" % (variant, np, "_per_body" if extra else "")
        out[name], s, stdout = run_variant(variant, scene, sets + extra, np,
                                           "geometric_coarsest_%s_%s" % (key, name), aggregate)
        check(s["status"] == "completed", "%s %s: completed" % (label, name))
        check("geometric coarse space: 3 levels" in stdout and LOGGED[variant] in stdout,
              "%s %s: the log names three levels and '%s'" % (label, name, LOGGED[variant]))
        per_solve[name] = s["linear_iterations"] / max(1, s["newton_iterations"])
        worst, where = largest_column_difference(direct, out[name], ("reactions.csv", "energy.csv"))
        check(worst <= 1e-6, "%s %s vs the direct solver: largest difference %.1e of its column's scale (%s)"
              " <= 1e-6" % (label, name, worst, where))
    for variant in ("ml3", "klu"):
        for name in out:
            if name.startswith(variant + "_np2"):
                worst, where = largest_column_difference(out[variant + "_np1"], out[name],
                                                         ("reactions.csv", "energy.csv"))
                check(worst <= 1e-6, "%s %s = np 1: largest difference %.1e of its column's scale (%s) <= 1e-6"
                      % (label, name, worst, where))
    if aggregate:
        check(per_solve["klu_np1"] <= per_solve["ml1_np1"],
              "%s: KLU on A_2 %.2f Krylov iterations per solve <= one ML cycle's %.2f"
              % (label, per_solve["klu_np1"], per_solve["ml1_np1"]))

# The automatic rule, on 2D boxes (elastic, one step).
for cells, expected in [(170, "2 levels, rows 58482, 14792; coarsest: ML x2"), (172, "coarsest: ML x1")]:
    os.environ.pop("ANVIL_GMG_LEVELS", None)
    for env in VARIANTS.values():
        for key in env:
            os.environ.pop(key, None)
    _, s, stdout = run("contrib/bench/elastic_block.prm",
                       ["Dimension=2", "Geometry/Blocks=body: 0, 0, 1, 1, %d, %d" % (cells, cells),
                        "Time/End time=0.5"] + GEOMETRIC, name="geometric_coarsest_rule_%d" % cells)
    check(s["status"] == "completed", "2D %d^2: completed" % cells)
    line = [l for l in stdout.splitlines() if "coarsest:" in l]
    check(line and expected in line[0], "2D %d^2: %s (log: %s)" % (cells, expected, line[0] if line else "none"))
finish()

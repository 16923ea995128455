"""The monolithic Newton's iterative linear solve (coupling/block_solve.cc:
GMRES with one AMG per field, the displacement block's on the rigid-body
modes, nodes aggregated as in the mechanics' own solve) gives the direct
solver's answer (KLU on the two-field matrix) on the thermal necking bar,
axisymmetric F-bar J2 with the heat of plastic flow, refined to 20 x 80
cells (3 402 displacement DoFs: above ML's coarse size, so the displacement
AMG has levels). Independent answer: the direct solve, exact to round-off;
the quantities of interest agree to 1e-8 relative (Newton to 1e-11, GMRES
to 1e-10 of |b|), and GMRES iterated (more than one iteration per solve)."""
from anvil_test import run, check, close, finish

SETS = ["Geometry/Radial cells=20", "Geometry/Axial cells=80", "Time/End time=0.3",
        "Physics/Coupling=monolithic", "Physics/Monolithic tolerance=1e-11",
        "Output/Field interval=0", "Output/Figure list="]
s = {}
for solver in ("direct", "iterative"):
    _, s[solver], _ = run("prm/necking_bar_thermal.prm", SETS + ["Physics/Monolithic linear solver=" + solver],
                          name="monolithic_iterative_" + solver)
    check(s[solver]["status"] == "completed", "%s: completed" % solver)
per_solve = s["iterative"]["linear_iterations"] / max(1, s["iterative"]["newton_iterations"])
check(per_solve > 1, "%d DoFs, %.1f GMRES iterations per Newton iteration (> 1: the AMG has levels)"
      % (s["iterative"]["dofs"], per_solve))
for k, v in s["direct"]["quantities_of_interest"].items():
    if isinstance(v, float) and v != 0:
        close(s["iterative"]["quantities_of_interest"][k], v, 1e-8, "%s: iterative = direct" % k)
finish()

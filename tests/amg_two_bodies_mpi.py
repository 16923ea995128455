"""GMRES + AMG on two bodies in contact, one body per process (the contact
strip of contrib/bench/contact_strip.prm, shortened: p4est orders the coarse
cells body by body, so on two processes each strip is one process's and the
contact surface is the whole process boundary).

Independent answer: the direct solve (KLU, one process), exact to round-off.
The iterative runs on one process, on two with ML's per-process aggregation
(the default) and on two with the coarse levels aggregated across the
processes (ANVIL_COARSE_AGGREGATION=coupled, build_amg(): ML's MIS from
level 1 on) must all give its reaction and energy histories to 1e-8 of their
largest value (Newton to 1e-12, the linear solves to 1e-10).

The hierarchy itself (ML's own report, "ML output" 10): on two processes
the coupled coarse aggregation must build as many levels as one process
does, and the per-process one more (its coarse aggregates cannot join the
two strips: half their size), or the test no longer tests what it claims."""
import os
import re
from anvil_test import run, check, finish, histories_agree

N = 4000  # cells along the upper strip: 48 006 DoFs, three AMG levels on one process, four per process
SETS = ["Geometry/Blocks=lower: 0, 0, %g, 0.02, %d, 2; upper: 0, 0.02, %g, 0.04, %d, 2"
        % (N / 100, N - 1, N / 100, N),
        "Boundary conditions/Displacement=lower.bottom: ux = 0, uy = 0; upper.left: ux = 0",
        "Mechanics/Newton/Residual tolerance=1e-12", "Mechanics/Linear solver/Tolerance=1e-10",
        "Time/End time=0.5"]
SCENE = "contrib/bench/contact_strip.prm"


def levels(stdout):
    """ML's level count of every hierarchy built ("Number of actual levels")."""
    return [int(n) for n in re.findall(r"Number of actual levels : (\d+)", stdout)]


out, counts = {}, {}
runs = [("direct", 1, "direct", None), ("iterative_np1", 1, "iterative", None),
        ("iterative_np2", 2, "iterative", None), ("coupled_np2", 2, "iterative", "coupled")]
for name, np, solver, aggregation in runs:
    os.environ["ANVIL_ML_PARAMETERS"] = "ML output:int=10"
    if aggregation:
        os.environ["ANVIL_COARSE_AGGREGATION"] = aggregation
    else:
        os.environ.pop("ANVIL_COARSE_AGGREGATION", None)
    out[name], s, stdout = run(SCENE, SETS + ["Mechanics/Linear solver/Type=" + solver], np=np,
                               name="amg_two_bodies_" + name)
    check(s["status"] == "completed" and s["processes"] == np, "%s: completed on %d process(es)" % (name, np))
    counts[name] = levels(stdout)
    if solver == "iterative":
        check(counts[name] != [], "%s: %d hierarchies of %s levels, %d Krylov iterations in %d Newton"
              % (name, len(counts[name]), sorted(set(counts[name])), s["linear_iterations"],
                 s["newton_iterations"]))
os.environ.pop("ANVIL_ML_PARAMETERS", None)
os.environ.pop("ANVIL_COARSE_AGGREGATION", None)

one = max(counts["iterative_np1"] or [0])
check(max(counts["coupled_np2"] or [0]) == one,
      "np 2, coupled coarse aggregation: %d levels as on one process (%d)" % (max(counts["coupled_np2"] or [0]), one))
check(max(counts["iterative_np2"] or [0]) > one,
      "np 2, per-process aggregation: %d levels, more than one process's %d (the case tests the coupling)"
      % (max(counts["iterative_np2"] or [0]), one))

for name in ("iterative_np1", "iterative_np2", "coupled_np2"):
    histories_agree(out["direct"], out[name], ("reactions.csv", "energy.csv"), 1e-8,
                    "direct (np 1) vs " + name)
finish()

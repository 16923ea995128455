"""The aggregate-block Gauss-Seidel fine-level smoother of the mechanics' AMG
(source/mechanics/block_smoother.cc, selected by ANVIL_FINE_SMOOTHER=blocks):
on a plastic F-bar block in 3D (10^3 cells, 3 993 DoFs, nearly incompressible
plastic tangent) GMRES needs at most 30 Krylov iterations per solve at 1e-8
relative with 4 sweeps per smoothing (issue 15's bound), fewer than with
ML's Chebyshev smoother, and with 2 sweeps (the smoother's default) the answer is the
direct solver's (KLU, exact to round-off): reaction-force and energy histories
agree to 1e-8 relative to their largest value (Newton to 1e-12, the linear
solves to 1e-10)."""
import os

from anvil_test import run, read_csv, check, finish

SETS = ["Dimension=3", "Geometry/Blocks=body: 0.1, 0, 0, 1.1, 1, 1, 10, 10, 10",
        "Boundary conditions/Displacement=bottom: ux = 0, uy = 0, uz = 0; top: ux = 0.05*t, uy = -0.1*t, uz = 0.02*t",
        "Mechanics/Element=F-bar", "Mechanics/Newton/Residual tolerance=1e-12", "Time/End time=0.5"]
out, per_solve = {}, {}
# (fine smoother, sweeps, linear tolerance): "blocks" against KLU at 1e-10,
# the Krylov counts at 1e-8 (Chebyshev for comparison).
RUNS = {"direct": ("chebyshev", 2, "1e-10"), "blocks": ("blocks", 2, "1e-10"),
        "chebyshev": ("chebyshev", 2, "1e-8"), "blocks, 4 sweeps": ("blocks", 4, "1e-8")}
for solver, (smoother, sweeps, tolerance) in RUNS.items():
    os.environ["ANVIL_FINE_SMOOTHER"], os.environ["ANVIL_BLOCK_SWEEPS"] = smoother, str(sweeps)
    out[solver], s, _ = run("tests/plastic_block.prm",
                            SETS + ["Mechanics/Linear solver/Type=" + ("direct" if solver == "direct" else "iterative"),
                                    "Mechanics/Linear solver/Tolerance=" + tolerance],
                            name="block_smoother_" + solver.replace(", ", "_").replace(" ", "_"))
    check(s["status"] == "completed", "%s: completed" % solver)
    per_solve[solver] = s["linear_iterations"] / max(1, s["newton_iterations"])
dofs = s["dofs"]
check(1 < per_solve["blocks, 4 sweeps"] <= 30,
      "%d DoFs: %.1f Krylov iterations per solve at 1e-8, 4 block sweeps per smoothing (1 < . <= 30)"
      % (dofs, per_solve["blocks, 4 sweeps"]))
check(per_solve["blocks, 4 sweeps"] < per_solve["chebyshev"],
      "fewer than with Chebyshev 2 (%.1f)" % per_solve["chebyshev"])
for f in ("reactions.csv", "energy.csv"):
    a, b = read_csv(out["direct"] + "/" + f), read_csv(out["blocks"] + "/" + f)
    keys = [k for k in a if k in b]
    scale = max(max(abs(x) for x in a[k]) for k in keys) or 1.0
    worst = max(abs(x - y) for k in keys for x, y in zip(a[k], b[k]))
    check(worst <= 1e-8 * scale, "%s: direct vs block-smoothed AMG largest difference %.2e (relative %.1e <= 1e-8)"
          % (f, worst, worst / scale))
finish()

"""Two fine-level remedies of the mechanics' AMG for the nearly incompressible
plastic F-bar tangent, on a distorted plastic block in 3D (10^3 cells, 3 993
DoFs; doc/linear_solver.md):
- the aggregate-block Gauss-Seidel smoother (source/mechanics/block_smoother.cc,
  ANVIL_FINE_SMOOTHER=blocks) with 4 sweeps per smoothing,
- the isochoric modes in the near-null space with Chebyshev 5
  (Mechanics/Linear solver/AMG isochoric modes = true, AMG smoother degree = 5;
  session 14),
each need at most 30 Krylov iterations per solve at 1e-8 relative (issue 15's
bound), fewer than the default AMG (rigid-body modes, Chebyshev 2); and with
either (the block smoother at its default 2 sweeps) the answer is the direct
solver's (KLU, exact to round-off): every reaction-force and energy column
agrees to 1e-6 of its own scale (floored at 1e-6 of its file's largest value;
Newton to 1e-12, the linear solves to 1e-10)."""
import os

from anvil_test import run, check, finish, largest_column_difference

SETS = ["Dimension=3", "Geometry/Blocks=body: 0.1, 0, 0, 1.1, 1, 1, 10, 10, 10",
        "Boundary conditions/Displacement=bottom: ux = 0, uy = 0, uz = 0; top: ux = 0.05*t, uy = -0.1*t, uz = 0.02*t",
        "Mechanics/Element=F-bar", "Mechanics/Newton/Residual tolerance=1e-12", "Time/End time=0.5",
        # AMG's smoothers are under test (the 3D default 'automatic' picks geometric on this block).
        "Mechanics/Linear solver/Preconditioner=AMG"]
BLOCKS = {"ANVIL_FINE_SMOOTHER": "blocks", "ANVIL_BLOCK_SWEEPS": "2"}
# The default became 'automatic' (session 17: isochoric modes, Chebyshev 6, ratio 100 once plastic):
# the runs below keep the settings they were written for.
RIGID = ["Mechanics/Linear solver/AMG isochoric modes=false"]
ISOCHORIC = ["Mechanics/Linear solver/AMG isochoric modes=true", "Mechanics/Linear solver/AMG smoother degree=5",
             "Mechanics/Linear solver/AMG Chebyshev ratio=10"]
# name: (environment, scene settings, linear tolerance); "direct" is KLU.
RUNS = {"direct": ({}, [], "1e-10"), "blocks": (BLOCKS, RIGID, "1e-10"), "isochoric": ({}, ISOCHORIC, "1e-10"),
        "chebyshev": ({}, RIGID, "1e-8"), "blocks, 4 sweeps": (dict(BLOCKS, ANVIL_BLOCK_SWEEPS="4"), RIGID, "1e-8"),
        "isochoric, 1e-8": ({}, ISOCHORIC, "1e-8")}
out, per_solve = {}, {}
for name, (environment, settings, tolerance) in RUNS.items():
    for k in BLOCKS:
        os.environ.pop(k, None)
    os.environ.update(environment)
    out[name], s, _ = run("tests/plastic_block.prm",
                          SETS + settings +
                          ["Mechanics/Linear solver/Type=" + ("direct" if name == "direct" else "iterative"),
                           "Mechanics/Linear solver/Tolerance=" + tolerance],
                          name="block_smoother_" + name.replace(", ", "_").replace(" ", "_"))
    check(s["status"] == "completed", "%s: completed" % name)
    per_solve[name] = s["linear_iterations"] / max(1, s["newton_iterations"])
dofs = s["dofs"]
for name in ("blocks, 4 sweeps", "isochoric, 1e-8"):
    check(1 < per_solve[name] <= 30, "%s: %d DoFs, %.1f Krylov iterations per solve at 1e-8 (1 < . <= 30)"
          % (name, dofs, per_solve[name]))
    check(per_solve[name] < per_solve["chebyshev"],
          "%s: fewer than the default AMG (rigid-body modes, Chebyshev 2: %.1f)" % (name, per_solve["chebyshev"]))
for name in ("blocks", "isochoric"):
    worst, where = largest_column_difference(out["direct"], out[name], ("reactions.csv", "energy.csv"))
    check(worst <= 1e-6, "direct vs %s: largest difference %.1e of its column's scale (%s) <= 1e-6"
          % (name, worst, where))
finish()

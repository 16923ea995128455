"""The iterative mechanics solver (GMRES + AMG on the rigid-body modes,
source/mechanics/linear_solver.cc) gives the direct solver's answer (KLU) to
solver tolerance on plastic F-bar blocks, plane strain and 3D: the
reaction-force and energy histories agree to 1e-8 relative to their largest
value (Newton to 1e-12, the linear solves to 1e-10). Independent answer:
the direct solve is exact to round-off. The meshes are large enough
(> 2000 DoFs, ML's coarse size) for the AMG to have levels: the test also
checks that GMRES iterated (more than one Krylov iteration per solve).
The same with the AMG hierarchy kept across Newton iterations and steps
(Mechanics/Linear solver/AMG rebuild growth = 1.5, ReusedAMG): the kept
hierarchy changes the iterations, not the answer."""
from anvil_test import run, check, finish, histories_agree

PLASTIC = ["Mechanics/Newton/Residual tolerance=1e-12", "Mechanics/Linear solver/Tolerance=1e-10",
           "Time/End time=0.5",
           # AMG is under test (the 3D default 'automatic' picks geometric on this block).
           "Mechanics/Linear solver/Preconditioner=AMG"]
cases = [
    ("plane strain", ["Geometry/Blocks=body: 0.1, 0, 1.1, 1, 40, 40"]),
    ("3D", ["Dimension=3", "Geometry/Blocks=body: 0.1, 0, 0, 1.1, 1, 1, 10, 10, 10",
            "Boundary conditions/Displacement=bottom: ux = 0, uy = 0, uz = 0; top: ux = 0.05*t, uy = -0.1*t, uz = 0.02*t"]),
]
for name, sets in cases:
    tag = name.replace(" ", "_")
    o = {}
    for solver in ("direct", "iterative", "kept"):
        extra = ["Mechanics/Linear solver/AMG rebuild growth=1.5"] if solver == "kept" else []
        o[solver], s, _ = run("tests/plastic_block.prm",
                              PLASTIC + sets + extra + ["Mechanics/Linear solver/Type=" +
                                                        ("direct" if solver == "direct" else "iterative")],
                              name="iterative_solver_%s_%s" % (tag, solver))
        check(s["status"] == "completed", "%s, %s: completed" % (name, solver))
        if solver != "direct":
            per_solve = s["linear_iterations"] / max(1, s["newton_iterations"])
            check(per_solve > 1, "%s: %d DoFs, %.1f Krylov iterations per solve (> 1: the AMG has levels)"
                  % (name, s["dofs"], per_solve))
    for solver in ("iterative", "kept"):
        histories_agree(o["direct"], o[solver], ("reactions.csv", "energy.csv"), 1e-8,
                        "%s: direct vs %s" % (name, solver))
finish()

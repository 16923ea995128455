"""MueLu as the mechanics' AMG (Mechanics/Linear solver/AMG package = MueLu,
source/mechanics/muelu_preconditioner.cc, loaded as libanvil-muelu.so):
GMRES + MueLu gives the direct solver's answer (KLU, exact to round-off) to
solver tolerance on plastic F-bar blocks, plane strain and 3D (the 3D block
distorted), on 1 process and (plane strain) on 2: every reaction-force and
energy column agrees to 1e-6 of its own scale (floored at 1e-6 of its
file's largest value; Newton to 1e-12, the linear solves to 1e-10). The
meshes are larger than the coarse size (2000 rows), so the hierarchy has
levels: GMRES iterates (more than one Krylov iteration per solve). A
misspelled package is one error line naming the entry (exit 2)."""
import os
import subprocess

from anvil_test import ANVIL, SOURCE_DIR, run, check, finish, largest_column_difference

BASE = ["Mechanics/Element=F-bar", "Mechanics/Newton/Residual tolerance=1e-12",
        "Mechanics/Linear solver/Tolerance=1e-10", "Time/End time=0.5"]
CASES = {
    "plane strain": ["Geometry/Blocks=body: 0.1, 0, 1.1, 1, 40, 40"],
    "3D": ["Dimension=3", "Geometry/Blocks=body: 0.1, 0, 0, 1.1, 1, 1, 10, 10, 10",
           "Boundary conditions/Displacement=bottom: ux = 0, uy = 0, uz = 0; "
           "top: ux = 0.05*t, uy = -0.1*t, uz = 0.02*t"],
}
MUELU = ["Mechanics/Linear solver/Type=iterative", "Mechanics/Linear solver/AMG package=MueLu"]
for case, sets in CASES.items():
    tag = case.replace(" ", "_")
    direct, s, _ = run("tests/plastic_block.prm", BASE + sets + ["Mechanics/Linear solver/Type=direct"],
                       name="muelu_%s_direct" % tag)
    check(s["status"] == "completed", "%s, direct: completed" % case)
    for np in ((1, 2) if case == "plane strain" else (1,)):
        out, s, _ = run("tests/plastic_block.prm", BASE + sets + MUELU, np=np, name="muelu_%s_np%d" % (tag, np))
        check(s["status"] == "completed", "%s, MueLu np %d: completed" % (case, np))
        per_solve = s["linear_iterations"] / max(1, s["newton_iterations"])
        check(per_solve > 1, "%s, MueLu np %d: %d DoFs, %.1f Krylov iterations per solve (> 1: levels)"
              % (case, np, s["dofs"], per_solve))
        worst, where = largest_column_difference(direct, out, ("reactions.csv", "energy.csv"))
        check(worst <= 1e-6, "%s: direct vs MueLu np %d: largest difference %.1e of its column's scale (%s) <= 1e-6"
              % (case, np, worst, where))

# A bad value: one line naming the entry and the valid names.
cmd = [ANVIL, os.path.join(SOURCE_DIR, "tests/plastic_block.prm"), "--set", "Mechanics/Linear solver/AMG package=Muelu"]
p = subprocess.run(cmd, capture_output=True, text=True,
                   env=dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1"))
lines = [x for x in p.stderr.strip().splitlines() if x.strip()]
check(p.returncode == 2 and len(lines) == 1 and "AMG package" in lines[0] and "Muelu" in lines[0],
      "AMG package = Muelu: exit %d, %r" % (p.returncode, lines))
finish()

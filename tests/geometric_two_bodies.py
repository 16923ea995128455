"""The geometric coarse space from the mesh hierarchy (source/mechanics/
coarse_space_prolongation.cc) on two J2 bodies meshed as blocks refined once
(tests/geometric_two_bodies.prm), 2D and 3D, and on a curved 3D tube refined once
(tests/geometric_tube.prm): GMRES to 1e-10 reaches the
direct solver's (KLU) answer, every reaction and energy column to 1e-6 of its
scale; two processes (space-filling curve and per body) give np 1's answer;
and the same two blocks unrefined are refused with one line naming
Geometry/Global refinements."""
import os
import subprocess

from anvil_test import ANVIL, SOURCE_DIR, WORK_DIR, run, check, finish, largest_column_difference

SCENE = "tests/geometric_two_bodies.prm"
THREE_D = ["Dimension=3",
           "Geometry/Blocks=a: 0, 0, 0, 1, 1, 1, 4, 4, 4; b: 1.5, 0, 0, 2.5, 0.5, 1, 4, 2, 4",
           "Boundary conditions/Displacement=a.bottom: ux = 0, uy = 0, uz = 0; a.top: uy = -0.01*t; "
           "b.bottom: ux = 0, uy = 0, uz = 0; b.top: ux = 0.003*t, uy = -0.006*t, uz = 0.002*t"]
DIRECT = ["Mechanics/Linear solver/Type=direct"]
PER_BODY = ["Geometry/Partition=per body"]
for label, scene, dim_sets, runs in [
        ("2D", SCENE, [], [("direct", DIRECT, 1), ("geometric", [], 1), ("np2", [], 2), ("np2_per_body", PER_BODY, 2)]),
        ("3D", SCENE, THREE_D, [("direct", DIRECT, 1), ("geometric", [], 1), ("np2", [], 2)]),
        ("3D tube", "tests/geometric_tube.prm", [], [("direct", DIRECT, 1), ("geometric", [], 1), ("np2", [], 2)])]:
    out, per_solve = {}, {}
    for name, extra, np in runs:
        out[name], s, _ = run(scene, dim_sets + extra, np=np,
                              name="geometric_two_bodies_%s_%s" % (label.replace(" ", "_"), name))
        check(s["status"] == "completed" and s["steps"] == 4, "%s %s: completed in 4 steps" % (label, name))
        per_solve[name] = s["linear_iterations"] / max(1, s["newton_iterations"])
    check(per_solve["geometric"] > 1, "%s: %.1f Krylov iterations per solve" % (label, per_solve["geometric"]))
    for a, b in [("direct", "geometric")] + [("geometric", n) for n, _, np in runs if np == 2]:
        worst, where = largest_column_difference(out[a], out[b], ("reactions.csv", "energy.csv"))
        check(worst <= 1e-6, "%s %s vs %s: largest difference %.1e of its column's scale (%s) <= 1e-6"
              % (label, a, b, worst, where))

p = subprocess.run([ANVIL, os.path.join(SOURCE_DIR, SCENE), "--set", "Geometry/Global refinements=0", "--set",
                    "Output/Directory=" + os.path.join(WORK_DIR, "output", "geometric_two_bodies_unrefined")],
                   capture_output=True, text=True, env=dict(os.environ, DEAL_II_NUM_THREADS="1"))
lines = [l for l in p.stderr.strip().splitlines() if l.strip()]
check(p.returncode == 2 and len(lines) == 1 and "Geometry/Global refinements" in lines[0],
      "two unrefined blocks: refused (status %d) in one line naming Geometry/Global refinements: %s"
      % (p.returncode, p.stderr.strip()[:300]))
finish()

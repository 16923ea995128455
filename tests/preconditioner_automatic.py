"""Mechanics/Linear solver/Preconditioner = automatic (the default;
source/mechanics/linear_solver.cc's rule, doc/linear_solver.md "Session 22:
the default"), on the plastic F-bar block of contrib/bench/elastic_block.prm:

- 3D, 4^3 cells refined once (2187 DoFs, iterative): the log names the
  geometric cycle, and the answer is the direct solver's (KLU, exact to
  round-off): every reaction and energy column to 1e-6 of its scale (GMRES
  to 1e-8); two processes give one process's answer and the same choice;
- 3D, 9^3 cells unrefined (odd: no coarser level): automatic runs AMG, no
  refusal, KLU's answer; an explicit 'geometric' on that mesh is refused in
  one line naming Geometry/Global refinements (exit status 2);
- 3D refined once with AMG rebuild growth > 0 (an AMG-only option): AMG;
- 2D, 24^2 cells refined once (iterative forced): AMG.
The choice is read from the log line 'Mechanics: iterative solver,
preconditioner ...', which is what a user sees."""
import os
import re
import subprocess

from anvil_test import ANVIL, SOURCE_DIR, WORK_DIR, run, check, finish, largest_column_difference

SCENE = "contrib/bench/elastic_block.prm"
J2 = ["Mechanics/Element=F-bar", "Bodies/body/Material/Model=J2",
      "Bodies/body/Material/Hardening/Initial yield stress=300",
      "Bodies/body/Material/Hardening/Hardening modulus=1000"]
AUTOMATIC = ["Mechanics/Linear solver/Preconditioner=automatic", "Mechanics/Linear solver/Type=iterative"]
DIRECT = ["Mechanics/Linear solver/Type=direct"]


def block3(n, refinements):
    return ["Dimension=3", "Geometry/Blocks=body: 0, 0, 0, 1, 1, 1, %d, %d, %d" % (n, n, n),
            "Geometry/Global refinements=%d" % refinements,
            "Boundary conditions/Displacement=front: ux = 0, uy = 0, uz = 0; back: uz = -0.05*t"] + J2


def picked(stdout):
    """The preconditioner the log names (None if no iterative solve)."""
    m = re.findall(r"^Mechanics: iterative solver, preconditioner (\S+)(.*)$", stdout, re.M)
    return (m[0][0], m[0][1].strip(), len(m)) if m else (None, "", 0)


def same_as_direct(label, out, out_direct):
    worst, where = largest_column_difference(out_direct, out, ("reactions.csv", "energy.csv"))
    check(worst <= 1e-6, "%s: against KLU, largest difference %.1e of its column's scale (%s) <= 1e-6"
          % (label, worst, where))


# 3D refined once: geometric, KLU's answer, np 2 = np 1.
refined = block3(4, 1)
out_direct, _, _ = run(SCENE, refined + DIRECT, name="preconditioner_automatic_3d_direct")
out = {}
for np in (1, 2):
    out[np], s, stdout = run(SCENE, refined + AUTOMATIC, np=np, name="preconditioner_automatic_3d_np%d" % np)
    choice, why, lines = picked(stdout)
    check(s["status"] == "completed" and s["dofs"] > 2000,
          "3D refined, np %d: completed, %d DoFs (above the 3D direct limit)" % (np, s["dofs"]))
    check(choice == "geometric" and "automatic" in why and lines == 1,
          "3D refined once, np %d: automatic picks geometric, said once in the log (%s %s, %d lines)"
          % (np, choice, why, lines))
    check(s["linear_iterations"] > s["newton_iterations"],
          "3D refined, np %d: GMRES iterated (%.1f Krylov per solve)"
          % (np, s["linear_iterations"] / max(1, s["newton_iterations"])))
    same_as_direct("3D refined once, np %d" % np, out[np], out_direct)
worst, where = largest_column_difference(out[1], out[2], ("reactions.csv", "energy.csv"))
check(worst <= 1e-6, "3D refined once, automatic: np 2 vs np 1, largest difference %.1e (%s) <= 1e-6" % (worst, where))

# 3D refined once, AMG rebuild growth > 0 (a kept AMG hierarchy was asked for): AMG.
_, s, stdout = run(SCENE, refined + AUTOMATIC + ["Mechanics/Linear solver/AMG rebuild growth=1.5",
                                                 "Time/End time=0.5"],
                   name="preconditioner_automatic_3d_kept")
choice, why, _ = picked(stdout)
check(s["status"] == "completed" and choice == "AMG" and "rebuild growth" in why,
      "3D refined, AMG rebuild growth = 1.5: automatic picks AMG (%s %s)" % (choice, why))

# 3D without a coarser level (9^3, odd): AMG, no refusal, KLU's answer.
odd = block3(9, 0)
out_odd_direct, _, _ = run(SCENE, odd + DIRECT, name="preconditioner_automatic_odd_direct")
out_odd, s, stdout = run(SCENE, odd + AUTOMATIC, name="preconditioner_automatic_odd")
choice, why, _ = picked(stdout)
check(s["status"] == "completed" and s["dofs"] > 2000, "3D 9^3: completed, %d DoFs" % s["dofs"])
check(choice == "AMG" and "no coarser" in why, "3D 9^3 unrefined: automatic picks AMG (%s %s)" % (choice, why))
same_as_direct("3D 9^3, automatic (AMG)", out_odd, out_odd_direct)
p = subprocess.run([ANVIL, os.path.join(SOURCE_DIR, SCENE)] +
                   [a for e in odd + ["Mechanics/Linear solver/Preconditioner=geometric",
                                      "Mechanics/Linear solver/Type=iterative",
                                      "Output/Directory=" + os.path.join(WORK_DIR, "output",
                                                                         "preconditioner_automatic_refused")]
                    for a in ("--set", e)],
                   capture_output=True, text=True, env=dict(os.environ, DEAL_II_NUM_THREADS="1"))
lines = [l for l in p.stderr.strip().splitlines() if l.strip()]
check(p.returncode == 2 and len(lines) == 1 and "Geometry/Global refinements" in lines[0],
      "3D 9^3, explicit geometric: refused (status %d) in one line: %s" % (p.returncode, p.stderr.strip()[:200]))

# 2D refined once, iterative: AMG.
_, s, stdout = run(SCENE, ["Dimension=2", "Geometry/Blocks=body: 0, 0, 1, 1, 24, 24", "Geometry/Global refinements=1"]
                   + J2 + AUTOMATIC, name="preconditioner_automatic_2d")
choice, why, _ = picked(stdout)
check(s["status"] == "completed" and choice == "AMG" and why == "(automatic: 2D)",
      "2D refined once: automatic picks AMG (%s %s)" % (choice, why))
finish()

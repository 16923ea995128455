"""The two-level preconditioner on the geometric coarse space
(Mechanics/Linear solver/Preconditioner = geometric; source/mechanics/
geometric_coarse_space.cc) on the 3D plastic F-bar block (8^3 cells, as
amg_plastic_default): GMRES to 1e-8 reaches the direct solver's (KLU) answer,
every reaction and energy column to 1e-6 of its scale, at <= 30 Krylov
iterations per solve; on two processes the same answer (to the solver
tolerance) and the same Krylov count to within 10 %. The smoothed levels in
single precision (the default since session 26, float_block_matrix.cc) take
no more iterations than in double (ANVIL_GMG_PRECISION=double) beyond 5 %. A block with odd
subdivisions is refused with one line naming the parameter."""
import os
import subprocess

from anvil_test import ANVIL, SOURCE_DIR, WORK_DIR, run, check, finish, largest_column_difference

J2 = ["Mechanics/Element=F-bar", "Bodies/body/Material/Model=J2",
      "Bodies/body/Material/Hardening/Initial yield stress=300",
      "Bodies/body/Material/Hardening/Hardening modulus=1000", "Dimension=3",
      "Boundary conditions/Displacement=front: ux = 0, uy = 0, uz = 0; back: uz = -0.05*t"]
BLOCK = "Geometry/Blocks=body: 0, 0, 0, 1, 1, 1, %d, %d, %d"
GEOMETRIC = ["Mechanics/Linear solver/Type=iterative", "Mechanics/Linear solver/Preconditioner=geometric"]
out, per_solve = {}, {}
for name, extra, np in [("direct", ["Mechanics/Linear solver/Type=direct"], 1),
                        ("geometric", GEOMETRIC, 1), ("geometric_np2", GEOMETRIC, 2),
                        ("geometric_double", GEOMETRIC, 1)]:
    # The cycle's levels in double (Epetra's matrices) as before session 26:
    # single precision must cost no iterations.
    if name == "geometric_double":
        os.environ["ANVIL_GMG_PRECISION"] = "double"
    out[name], s, _ = run("contrib/bench/elastic_block.prm", J2 + [BLOCK % (8, 8, 8)] + extra, np=np,
                          name="geometric_preconditioner_" + name)
    os.environ.pop("ANVIL_GMG_PRECISION", None)
    check(s["status"] == "completed", "%s: completed" % name)
    per_solve[name] = s["linear_iterations"] / max(1, s["newton_iterations"])
check(1 < per_solve["geometric"] <= 30, "%.1f Krylov iterations per solve at 1e-8 (1 < . <= 30)" % per_solve["geometric"])
check(per_solve["geometric"] <= 1.05 * per_solve["geometric_double"] + 0.5,
      "single-precision smoothing: %.1f Krylov iterations per solve against %.1f with the levels in double"
      % (per_solve["geometric"], per_solve["geometric_double"]))
for a, b in [("direct", "geometric"), ("geometric", "geometric_np2"), ("direct", "geometric_double")]:
    worst, where = largest_column_difference(out[a], out[b], ("reactions.csv", "energy.csv"))
    check(worst <= 1e-6, "%s vs %s: largest difference %.1e of its column's scale (%s) <= 1e-6" % (a, b, worst, where))
check(abs(per_solve["geometric_np2"] - per_solve["geometric"]) <= 0.1 * per_solve["geometric"],
      "np 2: %.1f Krylov iterations per solve against np 1's %.1f (within 10 %%)"
      % (per_solve["geometric_np2"], per_solve["geometric"]))
odd = subprocess.run([ANVIL, os.path.join(SOURCE_DIR, "contrib/bench/elastic_block.prm")] +
                     [a for e in J2 + [BLOCK % (7, 8, 8)] + GEOMETRIC + ["Output/Directory=" + os.path.join(WORK_DIR, "output", "geometric_preconditioner_odd")] for a in ("--set", e)],
                     capture_output=True, text=True, env=dict(os.environ, DEAL_II_NUM_THREADS="1"))
check(odd.returncode == 2 and "Preconditioner" in odd.stderr and "Geometry/Blocks" in odd.stderr,
      "7 x 8 x 8 cells: refused (status %d), naming the parameter: %s" % (odd.returncode, odd.stderr.strip()[:200]))
finish()

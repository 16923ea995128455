"""summary.json's linear_iterations is every Krylov iteration the run paid, a failed
solve's too (newton.cc adds the iterations of a solve that throws before the step is cut
back; they were missing before session 25). Checked against an independent count: the
per-solve log lines ANVIL_KRYLOV_LOG makes linear_solver.cc print ("Krylov: n" or
"Krylov: n failed"). 2D plastic F-bar block 48 x 48 with Maximum iterations = 18: some
plastic solves need more, fail, and the step is cut back; the run still completes. Each
failure is one line naming the count. One and two processes."""
import os

from anvil_test import run, check, finish

SETS = ["Dimension=2", "Geometry/Blocks=body: 0, 0, 1, 1, 48, 48", "Mechanics/Element=F-bar",
        "Bodies/body/Material/Model=J2", "Bodies/body/Material/Hardening/Initial yield stress=300",
        "Bodies/body/Material/Hardening/Hardening modulus=1000",
        "Mechanics/Linear solver/Preconditioner=AMG", "Mechanics/Linear solver/Type=iterative",
        "Mechanics/Linear solver/Maximum iterations=18", "Output/Verbosity=normal"]
os.environ["ANVIL_KRYLOV_LOG"] = "1"
for np in (1, 2):
    out, s, stdout = run("contrib/bench/elastic_block.prm", SETS, np=np, name="krylov_accounting_np%d" % np)
    check(s.get("status") == "completed", "np %d: completed" % np)
    lines = [l for l in stdout.splitlines() if l.startswith("Krylov:")]
    failed = [l for l in lines if l.split()[2] == "failed"]
    logged = sum(int(l.split()[1]) for l in lines)
    check(len(failed) >= 1, "np %d: %d of %d solves failed (Maximum iterations 18)" % (np, len(failed), len(lines)))
    check(s["linear_iterations"] == logged,
          "np %d: summary.json linear_iterations %d = the log's sum over every solve %d (failed: %d)"
          % (np, s["linear_iterations"], logged, sum(int(l.split()[1]) for l in failed)))
    reports = [l for l in stdout.splitlines() if "the linear solver did not converge in 18 iterations" in l]
    check(len(reports) == len(failed), "np %d: one failure line per failed solve (%d)" % (np, len(reports)))
finish()

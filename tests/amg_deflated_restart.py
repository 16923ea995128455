"""GMRES's continuation by GCRO-DR (amg_solver.cc, solve_gmres(); doc/linear_solver.md,
session 24): a solve that has not converged after one restart cycle, and has at least
halved its residual in it, continues from the iterate reached with GCRO-DR, which keeps
the harmonic Ritz vectors of smallest modulus across restarts. On the 2D plastic F-bar
block (48 x 48 cells) with `GMRES restart = 8` most plastic solves pass the first cycle,
so the rule is taken: the Krylov counts differ from GMRES(8)'s (ANVIL_GCRODR=0) and do
not exceed them in sum; every reaction and energy column equals KLU's to 1e-6 of its
scale; two processes give one process's answer. With the default restart (60) no solve
of this scene passes one cycle: newton.csv, reactions.csv and energy.csv are byte-equal
with and without the rule (a solve within one cycle is GMRES's, to the bit)."""
import filecmp
import os

from anvil_test import run, check, finish, largest_column_difference

SETS = ["Dimension=2", "Geometry/Blocks=body: 0, 0, 1, 1, 48, 48", "Mechanics/Element=F-bar",
        "Bodies/body/Material/Model=J2", "Bodies/body/Material/Hardening/Initial yield stress=300",
        "Bodies/body/Material/Hardening/Hardening modulus=1000",
        "Mechanics/Linear solver/Preconditioner=AMG", "Mechanics/Linear solver/Type=iterative"]
SHORT = ["Mechanics/Linear solver/GMRES restart=8"]
os.environ["ANVIL_KRYLOV_LOG"] = "1"


def counts(stdout):
    return [int(line.split()[1]) for line in stdout.splitlines() if line.startswith("Krylov:")]


def scene(name, extra=(), np=1, rule=True):
    if rule:
        os.environ.pop("ANVIL_GCRODR", None)
    else:
        os.environ["ANVIL_GCRODR"] = "0"
    out, s, stdout = run("contrib/bench/elastic_block.prm", SETS + list(extra), np=np,
                         name="amg_deflated_restart_" + name)
    check(s.get("status") == "completed", "%s: completed" % name)
    return out, counts(stdout)


on, k_on = scene("restart8", SHORT)
off, k_off = scene("restart8_off", SHORT, rule=False)
direct, _ = scene("direct", ["Mechanics/Linear solver/Type=direct"])
np2, k_np2 = scene("restart8_np2", SHORT, np=2)
check(any(k > 8 for k in k_on), "GMRES(8): solves past one cycle (%s)" % k_on)
check(k_on != k_off and sum(k_on) <= sum(k_off),
      "the continuation is taken: %d Krylov iterations in %d solves against GMRES(8)'s %d in %d"
      % (sum(k_on), len(k_on), sum(k_off), len(k_off)))
for name, out in (("GCRO-DR continuation", on), ("np 2", np2)):
    worst, where = largest_column_difference(direct, out, ("reactions.csv", "energy.csv"))
    check(worst <= 1e-6, "%s vs KLU: largest difference %.1e of its column's scale (%s) <= 1e-6" % (name, worst, where))
worst, where = largest_column_difference(on, np2, ("reactions.csv", "energy.csv"))
check(worst <= 1e-6, "np 2 vs np 1: %.1e (%s) <= 1e-6" % (worst, where))

default, k_default = scene("default")
default_off, _ = scene("default_off", rule=False)
check(max(k_default) <= 60, "restart 60: every solve within one cycle (%d at most)" % max(k_default))
for f in ("newton.csv", "reactions.csv", "energy.csv"):
    check(filecmp.cmp(os.path.join(default, f), os.path.join(default_off, f), shallow=False),
          "restart 60: %s byte-equal with and without the rule" % f)
finish()

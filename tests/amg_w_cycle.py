"""The AMG W-cycle (Mechanics/Linear solver/AMG cycle; amg_solver.cc, linear_solver.cc;
doc/linear_solver.md, session 25). On the 2D plastic F-bar block (48 x 48 cells) with a
small coarse size, so that ML builds three or more levels and a W-cycle differs from a
V-cycle: 'automatic' runs V on the elastic solves and W once the isochoric modes are on
(the log line of each solve says which); W needs fewer Krylov iterations than V in sum
over the plastic solves; every reaction and energy column of both equals KLU's to 1e-6 of
its scale; two processes give one process's answer to 1e-6."""
import os

from anvil_test import run, check, finish, largest_column_difference

SETS = ["Dimension=2", "Geometry/Blocks=body: 0, 0, 1, 1, 48, 48", "Mechanics/Element=F-bar",
        "Bodies/body/Material/Model=J2", "Bodies/body/Material/Hardening/Initial yield stress=300",
        "Bodies/body/Material/Hardening/Hardening modulus=1000",
        "Mechanics/Linear solver/Preconditioner=AMG", "Mechanics/Linear solver/Type=iterative",
        "Mechanics/Linear solver/AMG coarse size=100"]
os.environ["ANVIL_KRYLOV_LOG"] = "1"


def solves(stdout):
    """(iterations, isochoric, cycle) of every solve's log line."""
    out = []
    for line in stdout.splitlines():
        if line.startswith("Krylov:"):
            words = line.replace(",", " ").split()
            out.append((int(words[1]), "isochoric" in words, words[-1]))
    return out


def scene(name, extra=(), np=1):
    out, s, stdout = run("contrib/bench/elastic_block.prm", SETS + list(extra), np=np,
                         name="amg_w_cycle_" + name)
    check(s.get("status") == "completed", "%s: completed" % name)
    return out, solves(stdout)


auto, k_auto = scene("automatic")
v, k_v = scene("V", ["Mechanics/Linear solver/AMG cycle=V"])
direct, _ = scene("direct", ["Mechanics/Linear solver/Type=direct"])
np2, k_np2 = scene("automatic_np2", np=2)

plastic = [k for k in k_auto if k[1]]
check(plastic and all(k[2] == "W" for k in plastic) and all(k[2] == "V" for k in k_auto if not k[1]),
      "automatic: W on the %d plastic solves, V on the %d elastic ones"
      % (len(plastic), len(k_auto) - len(plastic)))
check(all(k[2] == "V" for k in k_v), "AMG cycle = V: every solve a V-cycle")
w_sum = sum(k[0] for k in plastic)
v_sum = sum(k[0] for k in k_v if k[1])
check(w_sum < v_sum, "plastic solves: W %d Krylov iterations in %d solves < V %d in %d"
      % (w_sum, len(plastic), v_sum, len([k for k in k_v if k[1]])))
for name, out in (("W (automatic)", auto), ("V", v), ("W np 2", np2)):
    worst, where = largest_column_difference(direct, out, ("reactions.csv", "energy.csv"))
    check(worst <= 1e-6, "%s vs KLU: largest difference %.1e of its column's scale (%s) <= 1e-6"
          % (name, worst, where))
worst, where = largest_column_difference(auto, np2, ("reactions.csv", "energy.csv"))
check(worst <= 1e-6, "np 2 vs np 1: %.1e (%s) <= 1e-6" % (worst, where))
finish()

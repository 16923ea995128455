"""The AMG W-cycle (Mechanics/Linear solver/AMG cycle; amg_solver.cc, linear_solver.cc;
doc/linear_solver.md, session 25), on the 2D plastic F-bar block.
48 x 48 cells (4 802 DoFs) with a small coarse size, so that ML builds three or more levels
and a W-cycle differs from a V-cycle: 'automatic' runs V on every solve (below 100 000
DoFs); 'W' runs W on every solve and needs fewer Krylov iterations than V in sum over the
plastic solves; every reaction and energy column of both equals KLU's to 1e-6 of its
scale; two processes give one process's answer to 1e-6.
224 x 224 cells (101 250 DoFs), the first step: 'automatic' runs V on the elastic solves
and W on the plastic ones (the log line of each solve says which)."""
import os

from anvil_test import run, check, finish, largest_column_difference

J2 = ["Dimension=2", "Mechanics/Element=F-bar",
      "Bodies/body/Material/Model=J2", "Bodies/body/Material/Hardening/Initial yield stress=300",
      "Bodies/body/Material/Hardening/Hardening modulus=1000",
      "Mechanics/Linear solver/Preconditioner=AMG", "Mechanics/Linear solver/Type=iterative"]
SMALL = J2 + ["Geometry/Blocks=body: 0, 0, 1, 1, 48, 48", "Mechanics/Linear solver/AMG coarse size=100"]
os.environ["ANVIL_KRYLOV_LOG"] = "1"


def solves(stdout):
    """(iterations, isochoric, cycle) of every solve's log line."""
    out = []
    for line in stdout.splitlines():
        if line.startswith("Krylov:"):
            words = line.replace(",", " ").split()
            out.append((int(words[1]), "isochoric" in words, words[-1]))
    return out


def scene(name, sets, np=1):
    out, s, stdout = run("contrib/bench/elastic_block.prm", sets, np=np, name="amg_w_cycle_" + name)
    check(s.get("status") == "completed", "%s: completed" % name)
    return out, solves(stdout)


W = ["Mechanics/Linear solver/AMG cycle=W"]
auto, k_auto = scene("automatic", SMALL)
w, k_w = scene("W", SMALL + W)
direct, _ = scene("direct", SMALL + ["Mechanics/Linear solver/Type=direct"])
np2, _ = scene("W_np2", SMALL + W, np=2)

check(all(k[2] == "V" for k in k_auto), "automatic below 100 000 DoFs: V on all %d solves" % len(k_auto))
check(all(k[2] == "W" for k in k_w), "AMG cycle = W: W on all %d solves" % len(k_w))
w_sum = sum(k[0] for k in k_w if k[1])
v_sum = sum(k[0] for k in k_auto if k[1])
check(w_sum < v_sum, "plastic solves: W %d Krylov iterations in %d solves < V %d in %d"
      % (w_sum, len([k for k in k_w if k[1]]), v_sum, len([k for k in k_auto if k[1]])))
for name, out in (("V (automatic)", auto), ("W", w), ("W np 2", np2)):
    worst, where = largest_column_difference(direct, out, ("reactions.csv", "energy.csv"))
    check(worst <= 1e-6, "%s vs KLU: largest difference %.1e of its column's scale (%s) <= 1e-6"
          % (name, worst, where))
worst, where = largest_column_difference(w, np2, ("reactions.csv", "energy.csv"))
check(worst <= 1e-6, "W: np 2 vs np 1: %.1e (%s) <= 1e-6" % (worst, where))

_, k_large = scene("automatic_224", J2 + ["Geometry/Blocks=body: 0, 0, 1, 1, 224, 224", "Time/End time=0.25"])
plastic = [k for k in k_large if k[1]]
check(plastic and all(k[2] == "W" for k in plastic) and all(k[2] == "V" for k in k_large if not k[1]),
      "automatic at 101 250 DoFs: W on the %d plastic solves, V on the %d elastic ones"
      % (len(plastic), len(k_large) - len(plastic)))
finish()

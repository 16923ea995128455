"""Newton converges quadratically on a large-deformation elastic problem: the
cantilever under a follower pressure curls with rotations of tens of degrees.
With the exact tangent (material, geometric and load stiffness) the error
contracts as r_{k+1} ~ C r_k^2: the estimated order
p = log(r_{k+1}/r_k) / log(r_k/r_{k-1}) is printed and must approach 2."""
import math
from anvil_test import run, read_csv, check, finish

out, s, _ = run("prm/cantilever.prm", ["Mechanics/Newton/Residual tolerance=1e-13",
                                       "Mechanics/Newton/Displacement tolerance=1e-14",
                                       "Mechanics/Newton/Absolute residual tolerance=1e-9",
                                       "Output/Field interval=0"], name="newton_quadratic")
n = read_csv(out + "/newton.csv")
steps = sorted(set(int(x) for x in n["step"]))
orders = []
tip = s["quantities_of_interest"]["tip_uy"]
print("  tip deflection %.4f mm on a 10 mm beam" % tip)
for st in steps:
    r = [n["residual"][i] for i in range(len(n["step"])) if int(n["step"][i]) == st and n["converged"][i] == 1]
    # Orders from consecutive triples well above round-off (1e-10 of the first residual).
    floor = 1e-10 * r[0]
    rr = [x for x in r if x > floor]
    line = " ".join("%.2e" % x for x in r)
    p = [math.log(rr[k + 1] / rr[k]) / math.log(rr[k] / rr[k - 1]) for k in range(1, len(rr) - 1)
         if rr[k] < rr[k - 1] and rr[k + 1] < rr[k]]
    if p:
        orders.append(p[-1])
    print("  step %2d residuals: %s   orders: %s" % (st, line, " ".join("%.2f" % x for x in p)))
check(abs(tip) > 2.0, "the beam deflects by more than 20%% of its length (%.3f mm)" % tip)
check(len(orders) >= len(steps) // 2, "orders measured on %d of %d steps" % (len(orders), len(steps)))
orders.sort()
median = orders[len(orders) // 2]
check(median > 1.8, "median convergence order of the last contraction per step: %.2f (expected 2)" % median)
check(s["newton_iterations"] / s["steps"] <= 6, "mean Newton iterations per step %.2f <= 6" % (s["newton_iterations"] / s["steps"]))
finish()

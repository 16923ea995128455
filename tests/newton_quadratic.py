"""Newton converges quadratically on a large-deformation elastic problem (the
cantilever under a follower pressure curls with rotations of tens of degrees)
and on plastic steps (the necking bar, J2 with saturation hardening, F-bar,
axisymmetric). With the exact tangent (material, geometric and load
stiffness) the error contracts as r_{k+1} ~ C r_k^2: the estimated order
p = log(r_{k+1}/r_k) / log(r_k/r_{k-1}) of the last contraction above the
round-off floor is printed and must approach 2. The steps start from the
committed state (Extrapolate = false) so that every step shows the whole
Newton sequence."""
import math
from anvil_test import run, read_csv, check, finish

out, s, _ = run("prm/cantilever.prm", ["Mechanics/Newton/Residual tolerance=1e-13",
                                       "Mechanics/Newton/Displacement tolerance=1e-14",
                                       "Mechanics/Newton/Absolute residual tolerance=1e-9",
                                       "Mechanics/Newton/Extrapolate=false",
                                       "Output/Field interval=0"], name="newton_quadratic")
n = read_csv(out + "/newton.csv")
steps = sorted(set(int(x) for x in n["step"]))
orders = []
tip = s["quantities_of_interest"]["tip_uy"]
print("  tip deflection %.4f mm on a 10 mm beam" % tip)
for st in steps:
    r = [n["residual"][i] for i in range(len(n["step"])) if int(n["step"][i]) == st and n["converged"][i] == 1]
    # Orders from consecutive triples above round-off (1e-11 of the first
    # residual). The last residuals of the steps, 5e-11 to 3e-10 of 1.6 N,
    # follow the asymptotic contraction (order 3.1 on every step where they
    # count), so they are not round-off; a floor of 1e-10 excluded them on
    # about half the steps, and a round-off change of the iterates (2D
    # tangent kernel, same to 5e-16) tipped the median over to the
    # pre-asymptotic contraction (0.55).
    floor = 1e-11 * r[0]
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

# Plastic steps: the necking bar up to its load maximum (uniform plastic
# flow; after it the neck localizes and points switch between loading and
# unloading within a step), every tenth step printed.
out, s, _ = run("prm/necking_bar.prm", ["Mechanics/Newton/Residual tolerance=1e-11",
                                        "Mechanics/Newton/Displacement tolerance=1e-12",
                                        "Mechanics/Newton/Extrapolate=false", "Time/Time step=0.01",
                                        "Time/End time=0.4",
                                        "Output/Field interval=0", "Output/Verbosity=quiet"], name="newton_quadratic_plastic")
n = read_csv(out + "/newton.csv")
orders = []
for st in sorted(set(int(x) for x in n["step"])):
    r = [n["residual"][i] for i in range(len(n["step"])) if int(n["step"][i]) == st and n["converged"][i] == 1]
    if not r:
        continue
    floor = 1e-11 * r[0]
    rr = [x for x in r if x > floor]
    p = [math.log(rr[k + 1] / rr[k]) / math.log(rr[k] / rr[k - 1]) for k in range(1, len(rr) - 1)
         if rr[k] < rr[k - 1] and rr[k + 1] < rr[k]]
    if p:
        orders.append(p[-1])
    if st % 5 == 0:
        print("  plastic step %3d residuals: %s   orders: %s" % (st, " ".join("%.2e" % x for x in r), " ".join("%.2f" % x for x in p)))
orders.sort()
median = orders[len(orders) // 2]
check(median > 1.8, "plastic steps (necking bar): median order of the last contraction %.2f (expected 2)" % median)
finish()

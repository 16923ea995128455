"""The full crush of the tube impact, case 3 (prm/tube_impact.prm), on one
process, on two, and stopped at the step nearest t = 1.6 ms (Dz = 24.4 mm, mid-crush, two
folds formed) and resumed from its checkpoint; label `long`.

What must agree (issue 12): the drive-force history to solver tolerance up to
the first fold (Dz <= 5 mm: the first peak and the first fold's collapse),
and the restart to solver tolerance everywhere (it replays the same
arithmetic). After the first fold the np = 2 run may bifurcate (fold
formation is a buckling: Newton's tolerance, a partition-dependent summation
order, can pick another fold); the deviation of the force history and of the
mean force over the crush is reported and asserted loosely (mean within 3 %,
the same energy audit)."""
import os
from anvil_test import run, read_csv, check, close, finish

v = 15277.8
base = ["Output/Field interval=0", "Output/Verbosity=quiet"]
o1, s1, _ = run("prm/tube_impact.prm", base, name="tube_np1")
o2, s2, _ = run("prm/tube_impact.prm", base, np=2, name="tube_np2")
# Stop on a step boundary of the uninterrupted run (the one nearest 1.6 ms), so
# that the resumed run marches the same steps (an End time between two steps
# would shorten the last one and shift every step after it).
t_full = read_csv(o1 + "/reactions.csv")["time"]
t_stop = min(t_full, key=lambda x: abs(x - 1.6e-3))
oh, _, _ = run("prm/tube_impact.prm", base + ["Time/End time=%.17g" % t_stop], name="tube_restart")
check(os.path.exists(oh + "/checkpoint/state.txt"), "a checkpoint at t = %.7g ms" % (1e3 * t_stop))
_, sr, _ = run("prm/tube_impact.prm", base + ["Output/Restart from=" + oh + "/checkpoint"], name="tube_restart")


def history(out):
    r = read_csv(out + "/reactions.csv")
    return r["time"], [-f / 1000 for f in r["top_Fy"]]


def mean_force(t, F):
    W = sum(0.5 * (F[i] + F[i - 1]) * (t[i] - t[i - 1]) for i in range(1, len(t)))
    return W / t[-1]


t1, F1 = history(o1)
for label, out, s in (("np = 2", o2, s2), ("restart at %.4g ms" % (1e3 * t_stop), oh, sr)):
    t, F = history(out)
    same_steps = len(t) == len(t1) and max(abs(a - b) for a, b in zip(t, t1)) < 1e-12
    print("%s: %d steps (np = 1: %d), %s time steps, %d Newton iterations (np = 1: %d), wall %.1f s (np = 1: %.1f s)"
          % (label, len(t), len(t1), "the same" if same_steps else "different", s.get("newton_iterations", 0),
             s1.get("newton_iterations", 0), s.get("wall_time", 0), s1.get("wall_time", 0)))
    # compare at the common times
    common = {round(x * 1e9): i for i, x in enumerate(t1)}
    early = late = 0.0
    for j, x in enumerate(t):
        i = common.get(round(x * 1e9))
        if i is None:
            continue
        d = abs(F[j] - F1[i]) / max(F1)
        if v * x <= 5:
            early = max(early, d)
        else:
            late = max(late, d)
    m1, m = mean_force(t1, F1), mean_force(t, F)
    print("  drive force deviation (of the largest force): %.3g up to Dz = 5 mm, %.3g after; mean force %.3f kN vs "
          "%.3f kN (%+.3f %%)" % (early, late, m, m1, 100 * (m / m1 - 1)))
    check(early <= 1e-5, "%s: the force history up to the first fold equals np = 1's (%.2g <= 1e-5)" % (label, early))
    if label.startswith("restart"):
        check(late <= 1e-5, "restart: the force history after it equals the uninterrupted run's (%.2g <= 1e-5)" % late)
    close(m, m1, 0.03, "%s: mean drive force (kN)" % label)
    check(s["energy"]["balance_error"] <= 0.01, "%s: energy balance %.3g <= 1 %%" % (label, s["energy"]["balance_error"]))
finish()

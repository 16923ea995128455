"""Patch test: a homogeneous finite stretch (x, y) -> (l1 x, l2 y) imposed on the
boundary of a distorted mesh gives one uniform stress in every cell, equal to the
closed form of the hypoelastic (Jaumann) law for coaxial stretching without
rotation: sigma = lambda tr(e) I + 2 G e with e = (ln l1, ln l2, 0) logarithmic
strains. The Hughes-Winget mid-point increments integrate ln with O(dt^2) error,
so the error must drop 4x when the step is halved."""
import math
from anvil_test import run, check, close, finish

E, nu = 1000.0, 0.3
lam = E * nu / ((1 + nu) * (1 - 2 * nu))
G = E / (2 * (1 + nu))
l1, l2 = 1.5, 0.8
bc = ("Boundary conditions/Displacement=" + "; ".join(
    "%s: ux = %g*t*x, uy = %g*t*y" % (b, l1 - 1, l2 - 1) for b in ("left", "right", "bottom", "top")))
e1, e2 = math.log(l1), math.log(l2)
exact = {"sxx": lam * (e1 + e2) + 2 * G * e1, "syy": lam * (e1 + e2) + 2 * G * e2,
         "szz": lam * (e1 + e2), "sxy": 0.0}
errors = []
for steps in (20, 40):
    out, s, _ = run("tests/homogeneous.prm", [bc, "Time/Time step=%g" % (1.0 / steps)],
                    name="patch_stretch_%d" % steps)
    q = s["quantities_of_interest"]
    for c in ("sxx", "syy", "szz", "sxy"):
        spread = q[c + "_max"] - q[c + "_min"]
        check(abs(spread) <= 1e-10 * E, "%d steps: %s uniform over the distorted mesh (spread %.2e MPa)" % (steps, c, spread))
    err = max(abs(q[c + "_max"] - exact[c]) for c in exact)
    print("  %d steps: sxx = %.10f (closed form %.10f), max error %.3e MPa" % (steps, q["sxx_max"], exact["sxx"], err))
    close(q["sxx_max"], exact["sxx"], 2e-4, "%d steps: stress_xx" % steps)
    close(q["syy_max"], exact["syy"], 2e-4, "%d steps: stress_yy" % steps, atol=1e-3)
    errors.append(err)
order = math.log(errors[0] / errors[1], 2)
check(1.8 < order < 2.2, "observed order in time of the stress error: %.3f (expected 2)" % order)
finish()

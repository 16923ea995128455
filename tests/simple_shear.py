"""Simple shear to gamma = 2 of a hypoelastic body: the Jaumann rate has the
closed form sigma_xy = G sin(gamma), sigma_xx = -sigma_yy = G (1 - cos(gamma)),
sigma_zz = 0 (e.g. Dienes 1979). Hughes-Winget increments converge to it with
second order in the step.

Past gamma = pi/2 the Jaumann shear stress G sin(gamma) falls: the incremental
response softens, so a distorted mesh may (and does) bifurcate away from the
homogeneous state. The test therefore uses one element whose nodes all
follow the prescribed motion: the finite element pipeline (kinematics, update,
stress recovery) without the bifurcation."""
import math
from anvil_test import run, check, close, finish

E, nu = 1000.0, 0.3
G = E / (2 * (1 + nu))
gamma = 2.0
bc = "Boundary conditions/Displacement=" + "; ".join(
    "%s: ux = %g*t*y, uy = 0" % (b, gamma) for b in ("left", "right", "bottom", "top"))
exact = {"sxy": G * math.sin(gamma), "sxx": G * (1 - math.cos(gamma)), "syy": -G * (1 - math.cos(gamma)), "szz": 0}
errors = []
for steps in (100, 200):
    _, s, _ = run("tests/homogeneous.prm", [bc, "Time/Time step=%g" % (1.0 / steps), "Geometry/Random distortion=0", "Geometry/Blocks=body: 0, 0, 1, 1, 1, 1"], name="simple_shear_%d" % steps)
    q = s["quantities_of_interest"]
    err = max(abs(q[c + "_max"] - exact[c]) for c in exact) / G
    print("  %d steps: sxy = %.8f (G sin g = %.8f)  sxx = %.8f (G(1-cos g) = %.8f)  syy = %.8f  max error / G = %.3e"
          % (steps, q["sxy_max"], exact["sxy"], q["sxx_max"], exact["sxx"], q["syy_max"], err))
    for c in exact:
        close(q[c + "_max"], exact[c], 0, "%d steps: %s" % (steps, c), atol=2e-3 * G)
    errors.append(err)
order = math.log(errors[0] / errors[1], 2)
check(1.8 < order < 2.2, "observed order of the Jaumann integration: %.3f (expected 2)" % order)
finish()

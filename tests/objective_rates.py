"""Simple shear to gamma = 8 of a hypoelastic body with each objective rate
(Path/Objective rate of the material-point driver) against its closed form,
with order 2 in the step; and each rate through the finite element pipeline
(Mechanics/Objective rate; elements whose nodes all follow the motion, as
tests/simple_shear.py, on 1 and 2 processes), which must agree with the driver.

Closed forms (G the shear modulus, motion x = X + gamma Y, isochoric, szz = 0):
  Jaumann:      sxy = G sin(gamma), sxx = -syy = G (1 - cos(gamma))
  Green-Naghdi: tan(beta) = gamma/2 (the polar rotation angle), Dienes (1979):
                sxy = 2G cos(2b) [2b - 2 tan(2b) ln(cos b) - tan b]
                sxx = -syy = 4G [cos(2b) ln(cos b) + b sin(2b) - sin(b)^2]
  logarithmic:  the Hencky model sigma = 2G ln V (Xiao, Bruhns & Meyers 1997):
                with lambda = gamma/2 + sqrt(1 + gamma^2/4), r = sqrt(1 + gamma^2/4),
                ln V = (ln(lambda)/r) [[gamma/2, 1], [1, -gamma/2]], so
                sxy = 2G ln(lambda)/r, sxx = -syy = G gamma ln(lambda)/r."""
import math
import os
from anvil_test import SOURCE_DIR, run, run_point, read_csv, check, close, finish

E, nu = 1000.0, 0.3
G = E / (2 * (1 + nu))
gamma = 8.0


def closed_form(rate, g):
    if rate == "Jaumann":
        sxy, sxx = G * math.sin(g), G * (1 - math.cos(g))
    elif rate == "Green-Naghdi":
        b = math.atan(g / 2)
        sxy = 2 * G * math.cos(2 * b) * (2 * b - 2 * math.tan(2 * b) * math.log(math.cos(b)) - math.tan(b))
        sxx = 4 * G * (math.cos(2 * b) * math.log(math.cos(b)) + b * math.sin(2 * b) - math.sin(b) ** 2)
    else:
        lam, r = g / 2 + math.sqrt(1 + g * g / 4), math.sqrt(1 + g * g / 4)
        sxy, sxx = 2 * G * math.log(lam) / r, G * g * math.log(lam) / r
    return {"sxy": sxy, "sxx": sxx, "syy": -sxx, "szz": 0.0}


bc = "Boundary conditions/Displacement=" + "; ".join(
    "%s: ux = %g*t*y, uy = 0" % (b, gamma) for b in ("left", "right", "bottom", "top"))
point_prm = os.path.join(SOURCE_DIR, "prm", "material_point", "simple_shear.prm")
for rate in ("Jaumann", "Green-Naghdi", "logarithmic"):
    exact = closed_form(rate, gamma)
    tag = rate.lower().replace("-", "_")
    errors = []
    for steps in (400, 800):
        path, _, _ = run_point(point_prm, ["Path/Objective rate=" + rate, "Path/Deformation gradient=F12: %g*t" % gamma,
                                           "Path/Steps=%d" % steps, "Material/Elasticity/Young's modulus=%g" % E],
                               name="objective_rate_%s_%d" % (tag, steps))
        h = read_csv(path)
        q = {c: h[c][-1] for c in exact}
        err = max(abs(q[c] - exact[c]) for c in exact) / G
        print("  %-12s %3d steps: sxy/G = %.8f (closed form %.8f)  sxx/G = %.8f (%.8f)  max error/G = %.3e"
              % (rate, steps, q["sxy"] / G, exact["sxy"] / G, q["sxx"] / G, exact["sxx"] / G, err))
        errors.append(err)
    for c in exact:
        close(q[c], exact[c], 0, "%s, 800 steps: %s" % (rate, c), atol=5e-5 * G)
    order = math.log(errors[0] / errors[1], 2)
    check(1.8 < order < 2.2, "%s: observed order %.3f (expected 2)" % (rate, order))

# The finite element pipeline (Mechanics/Objective rate) gives the driver's
# answer for every rate, on one process and on two (two elements, so that
# each process owns one).
for rate in ("Jaumann", "Green-Naghdi", "logarithmic"):
    tag = rate.lower().replace("-", "_")
    h = read_csv(os.path.join(os.path.dirname(path), "objective_rate_%s_800.csv" % tag))
    for np in (1, 2):
        _, s, _ = run("tests/homogeneous.prm",
                      [bc, "Mechanics/Objective rate=" + rate, "Time/Time step=%g" % (1.0 / 800),
                       "Geometry/Random distortion=0", "Geometry/Blocks=body: 0, 0, 1, 1, %d, 1" % np],
                      np=np, name="objective_rate_fe_%s_np%d" % (tag, np))
        for c in ("sxy", "sxx", "syy"):
            close(s["quantities_of_interest"][c + "_max"], h[c][-1], 0,
                  "%s, np %d: finite element %s equals the driver's" % (rate, np, c), atol=1e-8 * G)
finish()

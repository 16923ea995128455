"""max and min of the mechanical fields in the quantities of interest run over
the quadrature points, not the cell averages (issue 16), and say so.

A strip one cell wide (1 x 10 cells on [0, 1] x [0, 1], plane strain) has
every node on its left or right face, so prescribing u_x = a x y, u_y = 0 on
both faces prescribes the whole (bilinear, Q1-exact) field: at every point
eps_xx = a y, eps_xy = a x / 2, eps_yy = 0 (standard Q1: F-bar would give
each point its cell centre's dilatation), so (small strain, a = 1e-4)

    sigma_xx = (lambda + 2 mu) a y,   sigma_xy = mu a x.

The 2 x 2 Gauss points nearest the top face sit at y_q = 0.95 + 0.05/sqrt(3),
those nearest x = 1 at x_q = 0.5 + 0.5/sqrt(3): the extrema are the closed
form there (to O(a), the finite-strain terms), while cell averages would give
the values at the cell centres (0.95 and 0.5), 3 % and 37 % lower: the check
fails for cell averages. The printout names what each extremum runs over.
"""
import math

from anvil_test import run, check, close, finish

E, nu, a = 1000.0, 0.3, 1e-4
lam, mu = E * nu / ((1 + nu) * (1 - 2 * nu)), E / (2 * (1 + nu))
g = 1 / math.sqrt(3)
bc = "ux = %g*t*x*y, uy = 0" % a
out, s, log = run("tests/homogeneous.prm", [
    "Geometry/Blocks=body: 0, 0, 1, 1, 1, 10", "Geometry/Random distortion=0",
    "Time/Time step=1", "Output/Verbosity=normal", "Mechanics/Element=standard",
    "Boundary conditions/Displacement=left: %s; right: %s" % (bc, bc),
    "Output/Quantities of interest=sxx_max: max(stress_xx); sxx_min: min(stress_xx); "
    "sxy_max: max(stress_xy); sxy_min: min(stress_xy); sxx_mean: mean(stress_xx)"], name="quadrature_extrema")
q = s["quantities_of_interest"]
expected = {"sxx_max": (lam + 2 * mu) * a * (0.95 + 0.05 * g), "sxx_min": (lam + 2 * mu) * a * (0.05 - 0.05 * g),
            "sxy_max": mu * a * (0.5 + 0.5 * g), "sxy_min": mu * a * (0.5 - 0.5 * g),
            "sxx_mean": (lam + 2 * mu) * a * 0.5}
centres = {"sxx_max": (lam + 2 * mu) * a * 0.95, "sxy_max": mu * a * 0.5}
for name, value in expected.items():
    where = "the volume mean" if name == "sxx_mean" else "the extreme Gauss point"
    close(q[name], value, 1e-3, "%s (closed form at %s%s)" % (
        name, where, ", cell centre gives %.6g" % centres[name] if name in centres else ""))
notes = s.get("quantities_of_interest_extrema", {})
check(notes.get("sxx_max") == "max(stress_xx) over quadrature points" and "sxx_mean" not in notes,
      "summary.json says what each extremum runs over: %s" % notes)
check("sxx_max = " in log and "(max(stress_xx) over quadrature points)" in log,
      "the printout says it: %s" % next((l.strip() for l in log.splitlines() if "sxx_max" in l), ""))
finish()

"""A boundary temperature that changes in time (thermal only).

A strip 40 x 1 mm, every face held at T_b(t) = 293 + a t (a = 100 K/s) from
T = 293 K. Away from its ends the strip is a slab of thickness H = 1 mm whose
transient decays as exp(-pi^2 kappa t / H^2) (kappa = k / (rho c); at t = 1 s,
exp(-206) for k = 50 and exp(-4100) for k = 1000), leaving the quasi-steady
profile of -kappa T'' = -a with T = T_b on both faces:

    T(y, t) = T_b(t) - a y (H - y) / (2 kappa),  centre lag a H^2 / (8 kappa).

Q1 elements give these nodal values exactly (1D Poisson with a constant
source, consistent load), and backward Euler is exact on a solution linear in
time, so the centre node must sit at 393 - a H^2/(8 kappa) at t = 1 s to
solver tolerance, and no node may leave [293, 393] K. Before the fix the heat
tangent dropped the Dirichlet columns (K_IB), and a stage's Newton step
(one step: the problem is linear) missed -gamma K_IB dg: 646 K (k = 50) and
5476 K (k = 1000) with backward Euler.
"""
from anvil_test import run, check, close, finish

RHO, C, A, H = 2.66e-9, 9e8, 100.0, 1.0
ramp = "293+100*t"
for k in (50.0, 1000.0):
    kappa = k / (RHO * C)
    lag = A * H ** 2 / (8 * kappa)
    for method, fixed, tol in (("backward Euler", 0.1, 1e-6), ("DIRK order 3", 0.0, 1e-3)):
        sets = ["Geometry/Blocks=strip: 0, 0, 40, 1, 20, 2",
                "Bodies/strip/Material/Elasticity/Density=%g" % RHO,
                "Bodies/strip/Material/Elasticity/Heat capacity=%g" % C,
                "Bodies/strip/Material/Thermal/Conductivity=%g" % k,
                "Heat/Time integration/Method=" + method,
                "Heat/Time integration/Fixed step size=%g" % fixed,
                "Heat/Boundary conditions/Temperature=" + "; ".join(
                    "%s: %s" % (b, ramp) for b in ("left", "right", "top", "bottom")),
                "Output/Probes=c: 20, 0.5",
                "Output/Quantities of interest=Tc: probe(c, temperature); Tmax: max(temperature); "
                "Tmin: min(temperature)",
                "Output/Field interval=0", "Output/Figure list=", "Output/Verbosity=quiet"]
        _, s, _ = run("prm/heat_half_space.prm", sets, name="heat_dirichlet_ramp")
        q = s["quantities_of_interest"]
        what = "k = %g, %s" % (k, method)
        print("  %s: centre %.6f K (closed form %.6f), max %.6f, min %.6f"
              % (what, q["Tc"], 393 - lag, q["Tmax"], q["Tmin"]))
        close(q["Tc"], 393 - lag, 0, what + ": centre lag a H^2/(8 kappa)", atol=tol + 1e-9 * 393)
        check(q["Tmax"] <= 393 + 1e-9 and q["Tmin"] >= 293 - 1e-9,
              what + ": every node within [293, 393] K (max %.4f)" % q["Tmax"])
finish()

"""The iterated staggered scheme and the convergence of the splits to it.

A plane-strain block of J2 metal with linear thermal softening is stretched
plastically by 20 % in 1 s (left and bottom on rollers); its plastic heat
(chi = 0.9) conducts to a convective top face (h = 1 mW/(mm^2 K), 293 K), so
conduction and heating act together within each step. For every time step
dt (fixed) the three coupled schemes run:

 - iterated staggered: mechanics and heat repeated within the step until the
   temperature changes by less than 1e-7 K (ARKode's own error is ~3e-9 K): the fixed point of the step, the
   monolithic backward-Euler answer. The contraction of the iteration is
   printed; it must be < 1 (here the coupling is weak: ~1e-3).
 - isothermal and adiabatic splits: one pass each. Their distance to the
   fixed point at the same dt is the splitting error; both splits are first
   order, so it must halve with dt (observed order 1 +- 0.15).

Quantities: the end force on the right face and the mean temperature.
"""
import math

from anvil_test import run, read_csv, check, close, finish

base = ["Bodies/body/Material/Model=J2",
        "Bodies/body/Material/Hardening/Initial yield stress=300",
        "Bodies/body/Material/Hardening/Hardening modulus=1000",
        "Bodies/body/Material/Elasticity/Young's modulus=200000",
        "Bodies/body/Material/Elasticity/Thermal expansion=1e-5",
        "Bodies/body/Material/Hardening/Thermal softening/Model=linear",
        "Bodies/body/Material/Hardening/Thermal softening/Softening coefficient=2e-3",
        "Bodies/body/Material/Hardening/Thermal softening/Reference temperature=293",
        "Geometry/Random distortion=0",
        "Boundary conditions/Displacement=left: ux = 0; bottom: uy = 0; right: ux = 0.2*t",
        "Heat/Boundary conditions/Convection=top: 1, 293",
        "Heat/Time integration/Relative tolerance=1e-11",
        "Heat/Time integration/Absolute tolerance=1e-9",
        "Physics/Staggered tolerance=1e-7",
        "Mechanics/Newton/Residual tolerance=1e-11",
        "Mechanics/Newton/Absolute residual tolerance=0",
        "Time/Growth factor=1",
        "Output/Quantities of interest=F: reaction(right, x); T: mean(temperature)"]
schemes = ("iterated staggered", "isothermal split", "adiabatic split")
steps = (10, 20, 40, 80)
Q = {}
for n in steps:
    dt = 1.0 / n
    for scheme in schemes:
        out, s, _ = run("tests/homogeneous.prm",
                        base + ["Physics/Coupling=" + scheme, "Time/Time step=%.17g" % dt,
                                "Time/Maximum time step=%.17g" % dt],
                        name="split_convergence_%s_%d" % (scheme.split()[0], n))
        Q[scheme, n] = s["quantities_of_interest"]
        check(s["steps"] == n and s["cut_backs"] == 0, "%s, %d steps: no cut-back" % (scheme, n))
        if scheme == "iterated staggered":
            th = read_csv(out + "/thermal.csv")
            its = th["staggered_iterations"]
            rho = max(th["staggered_contraction"])
            print("  iterated staggered, dt = 1/%d: %.2f iterations per step, largest contraction %.2e, "
                  "last change %.1e K" % (n, sum(its) / len(its), rho, max(th["staggered_change"])))
            check(0 < rho < 1, "the staggered iteration contracts (%.2e) at dt = 1/%d" % (rho, n))
            check(max(th["staggered_change"]) <= 1e-7, "every step converged to 1e-7 K")

for key, unit in (("F", "N"), ("T", "K")):
    print("%s (%s):" % (key, unit))
    print("  %6s %18s %14s %14s %7s %7s" % ("steps", "iterated", "isothermal-it", "adiabatic-it", "order", "order"))
    prev = None
    for n in steps:
        ref = Q["iterated staggered", n][key]
        e_iso = abs(Q["isothermal split", n][key] - ref)
        e_adi = abs(Q["adiabatic split", n][key] - ref)
        orders = ("", "")
        if prev:
            orders = (math.log2(prev[0] / e_iso), math.log2(prev[1] / e_adi))
        print("  %6d %18.10f %14.4e %14.4e %7s %7s" % (n, ref, e_iso, e_adi,
              *("%.3f" % o if o != "" else "" for o in orders)))
        if prev and n == steps[-1]:
            close(orders[0], 1.0, 0.15, "isothermal split -> fixed point, order in dt (%s)" % key)
            close(orders[1], 1.0, 0.15, "adiabatic split -> fixed point, order in dt (%s)" % key)
        prev = (e_iso, e_adi)
    # The fixed point itself as dt -> 0 (for information: the force hardly
    # depends on dt, its differences are at the level of the mechanics' own
    # tolerances).
    r = [Q["iterated staggered", n][key] for n in steps]
    print("  iterated staggered, successive differences: %s"
          % " ".join("%.3e" % abs(r[i] - r[i + 1]) for i in range(len(r) - 1)))
finish()

"""Impact of an elastic bar on a rigid wall (implicit dynamics + contact).

A steel bar, 100 x 10 mm, plane strain, nu = 0 (1D waves), moving at
v = 1000 mm/s hits a frictionless rigid wall. 1D wave theory: the wall force
is rho c v A = 394.97 N/mm while the bar touches, for 2L/c = 39.5 us, and the
bar leaves with its kinetic energy (c = sqrt(E/rho)).

Measured stability limit (doc/contact.md): with a penalty whose contact
frequency the step resolves, the midpoint rule (spectral radius 1) conserves
the energy; with a penalty 10x stiffer than that it pumps energy into the
chattering contact, and numerical damping (spectral radius 0.5) restores it.
"""
import math
from anvil_test import run, read_csv, check, close, finish

E, rho, v, L, H = 2e5, 7.8e-9, 1000.0, 100.0, 10.0
c = math.sqrt(E / rho)
F, T = rho * c * v * H, 2 * L / c
base = ["Mechanics/Dynamics/Initial velocity=ux = -%g" % v, "Boundary conditions/Displacement=bottom: uy = 0",
        "Contact/Pairs=impact", "Contact/Tools=wall", "Contact/impact/Slave=left", "Contact/impact/Master=wall",
        "Contact/impact/Penalty per=area", "Contact/wall/Type=plane", "Contact/wall/Point=-0.0001, 0",
        "Contact/wall/Normal=1, 0", "Time/End time=6e-5", "Time/Time step=4e-7"]


def impact(cn, rho_inf, name):
    out, s, _ = run("tests/dynamics_bar.prm", base + ["Contact/impact/Penalty normal=%g" % cn,
                                                    "Mechanics/Dynamics/Spectral radius=%g" % rho_inf], name=name)
    cc, e = read_csv(out + "/contact.csv"), read_csv(out + "/energy.csv")
    N, t = cc["impact_normal"], cc["time"]
    on = [t[i] for i in range(len(N)) if N[i] > 0]
    plateau = sorted(x for x in N if x > 0)[len(on) // 2]
    ratio = e["kinetic_energy"][-1] / e["kinetic_energy"][0]
    print("  c_N = %g N/mm^3, spectral radius %g: contact %.3g s (2L/c = %.3g), median force %.2f N/mm "
          "(rho c v A = %.2f), kinetic energy after/before %.4f, Newton %.2f per step"
          % (cn, rho_inf, on[-1] - on[0], T, plateau, F, ratio, s["newton_iterations"] / s["steps"]))
    return on[-1] - on[0], plateau, ratio, max(e["balance_error"])


duration, plateau, ratio, balance = impact(1e6, 1, "contact_impact")
close(plateau, F, 0.02, "wall force = rho c v A (N/mm)")
close(duration, T, 0.05, "contact time = 2L/c (s)")
check(0.95 < ratio <= 1.0 + 1e-6, "the bar leaves with its kinetic energy (%.4f; the rest vibrates)" % ratio)
check(balance < 1e-8, "work balance closes with the contact work (%.1e)" % balance)
_, plateau, ratio, _ = impact(1e7, 1, "contact_impact_stiff")
check(ratio > 1.05, "a penalty 10x stiffer than the step resolves, undamped: energy grows (%.2f) - the measured limit"
      % ratio)
_, plateau, ratio, _ = impact(1e7, 0.5, "contact_impact_damped")
close(plateau, F, 0.02, "with spectral radius 0.5 the stiff penalty gives rho c v A again")
check(ratio < 1.0, "and no energy is created (%.4f)" % ratio)
finish()

"""The monolithic scheme (doc/monolithic.md) against independent answers.

1. Stability (tests/split_stability.py's setting, doc/thermal.md "Stability of
   the splits"): an insulated thermoelastic plane-strain block pulled in the
   first step and then held, coupling number tau_v r = 1.5 and 10, where the
   isothermal split's temperature change is amplified by -tau_v r per step
   (diverges). The monolithic Newton must stay put after the loading step
   (amplification 0) at the closed-form loading-step temperature (the root
   given in split_stability.py; small-strain, so to 1e-4).

2. The thermal necking bar (prm/necking_bar_thermal.prm): the monolithic
   answer equals the converged iterated staggered answer when both integrate
   the heat equation by the same one-step method (backward Euler, one step per
   mechanical step) and the staggered iteration is converged tightly: both
   are then solutions of the same discrete equations, and differ by the
   iteration tolerances only."""
import math
import sys
from anvil_test import run, read_csv, check, close, finish

# --- 1. stability at tau > 1 (same material and loading as split_stability.py)
K, nu, rho, c_v, T0, s = 70000.0, 0.3, 2.7e-9, 0.9e9, 300.0, 10.0
r = 2 * (1 + nu) / 3
dt, steps = 0.1, 12


def beta_for(tau_v):
    return math.sqrt(tau_v * rho * c_v / (9 * K * T0))


def simulate(name, coupling, beta):
    sets = ["Physics/Coupling=" + coupling, "Heat/Initial temperature=%g" % T0,
            "Geometry/Random distortion=0", "Bodies/body/Material/Model=hypoelastic",
            "Bodies/body/Material/Elasticity/Young's modulus=0",
            "Bodies/body/Material/Elasticity/Bulk modulus=%g" % K,
            "Bodies/body/Material/Elasticity/Poisson's ratio=%g" % nu,
            "Bodies/body/Material/Elasticity/Density=%g" % rho,
            "Bodies/body/Material/Elasticity/Heat capacity=%.15g" % c_v,
            "Bodies/body/Material/Elasticity/Heat capacity at=constant volume",
            "Bodies/body/Material/Elasticity/Thermal expansion=%.15g" % beta,
            "Bodies/body/Material/Elasticity/Reference temperature=%g" % T0,
            "Boundary conditions/Displacement=left: ux = 0; bottom: uy = 0",
            "Boundary conditions/Pressure=right: -%g" % s,
            "Heat/Time integration/Relative tolerance=1e-10", "Heat/Time integration/Absolute tolerance=1e-10",
            "Mechanics/Newton/Residual tolerance=1e-11", "Mechanics/Newton/Absolute residual tolerance=1e-9",
            "Physics/Monolithic tolerance=1e-12",
            "Time/Time step=%g" % dt, "Time/End time=%g" % (dt * steps),
            "Time/Growth factor=1", "Time/Maximum time step=%g" % dt,
            "Output/Probes=c: 0.5, 0.5", "Output/Quantities of interest=T: mean(temperature)"]
    out, summary, _ = run("tests/homogeneous.prm", sets, name="monolithic_stability_" + name)
    T = read_csv(out + "/probes.csv")["c_temperature"]
    return T, [T[n + 1] - T[n] for n in range(len(T) - 1)], summary


def adiabatic_temperature(beta):
    a = 3 * K * beta * 2 * (1 + nu) * beta
    b = rho * c_v + 3 * K * beta * ((1 + nu) * s / (3 * K) + 2 * (1 + nu) * beta * T0)
    cc = 3 * K * beta * T0 * (1 + nu) * s / (3 * K)
    return (-b + math.sqrt(b * b - 4 * a * cc)) / (2 * a)


for tau_r in (1.5, 10.0):
    beta = beta_for(tau_r / r)
    T, d, summary = simulate("%g" % tau_r, "monolithic", beta)
    amp = [d[n] / d[n - 1] if d[n - 1] != 0 else 0.0 for n in range(2, 7)]
    # The isothermal split beside it (at tau_v r = 10 it inverts the block within the 12 steps).
    d_iso = simulate("isothermal_%g" % tau_r, "isothermal split", beta)[1] if tau_r < 2 else [1.0] * 7
    amp_iso = [d_iso[n] / d_iso[n - 1] for n in range(2, 7)]
    expected = adiabatic_temperature(beta)
    drift = max(abs(x - T[1]) for x in T[1:])
    print("tau_v r = %.1f: monolithic T = %s; closed form T0 + %.8f; Newton %.2f per step"
          % (tau_r, " ".join("%.6f" % x for x in T[:5]), expected, summary["newton_iterations"] / summary["steps"]))
    print("  amplification d_n/d_(n-1), steps 2-6: monolithic %s (|d_1| = %.3g K, then %s K); "
          "isothermal split %s (predicted %.2f; not run at tau_v r = 10: it inverts the block)"
          % (" ".join("%.2g" % x for x in amp), abs(d[0]), " ".join("%.1g" % abs(x) for x in d[1:6]),
             " ".join("%.3f" % x for x in amp_iso), -tau_r))
    close(T[1] - T0, expected, 1e-4, "monolithic: loading-step temperature change (K), tau_v r = %g" % tau_r)
    check(drift < 1e-7 * abs(expected),
          "monolithic is stable at tau_v r = %g: T drifts by %.2g K after loading" % (tau_r, drift))
    check(max(abs(x) for x in amp) < 1e-3, "monolithic amplification after loading < 1e-3 at tau_v r = %g" % tau_r)
    if tau_r < 2:
        check(abs(d_iso[-1] / d_iso[1]) > 50, "beside it the isothermal split diverges: |d| grew %.3g times"
              % abs(d_iso[-1] / d_iso[1]))

# --- 2. equality with the converged iterated staggered answer on the necking bar
if "--stability-only" in sys.argv:
    finish()
COMMON = ["Time/Time step=0.25", "Time/End time=5", "Time/Growth factor=1", "Output/Field interval=0",
          "Mechanics/Newton/Residual tolerance=1e-11",
          "Heat/Time integration/Method=backward Euler", "Heat/Time integration/Fixed step size=1e9"]
mono, sm, _ = run("prm/necking_bar_thermal.prm", COMMON + [
    "Physics/Coupling=monolithic", "Physics/Monolithic tolerance=1e-10"], name="monolithic_necking_bar")
stag, ss, _ = run("prm/necking_bar_thermal.prm", COMMON + [
    "Physics/Coupling=iterated staggered", "Physics/Staggered tolerance=1e-9", "Physics/Staggered iterations=100",
    "Heat/Time integration/Relative tolerance=1e-13", "Heat/Time integration/Absolute tolerance=1e-13"],
    name="monolithic_necking_bar_staggered")
check(sm["steps"] == ss["steps"], "same steps (%d, %d)" % (sm["steps"], ss["steps"]))
for f, cols in (("reactions.csv", ["top_Fy"]),
                ("probes.csv", ["neck_ux", "end_ux", "neck_temperature", "centre_temperature"])):
    a, b = read_csv(mono + "/" + f), read_csv(stag + "/" + f)
    for c in cols:
        scale = max(abs(x) for x in b[c])
        worst = max(abs(x - y) for x, y in zip(a[c], b[c]))
        print("  %-20s monolithic vs iterated staggered: largest difference %.3e (scale %.4g)" % (c, worst, scale))
        check(worst <= 1e-7 * scale, "necking bar %s: monolithic = iterated staggered to %.1e relative"
              % (c, worst / scale))
print("  wall time: monolithic %.1f s (%d Newton its), iterated staggered %.1f s (%d Newton its, %d staggered)"
      % (sm.get("wall_time", 0), sm["newton_iterations"], ss.get("wall_time", 0), ss["newton_iterations"],
         ss.get("heat", {}).get("staggered_iterations", 0)))
finish()

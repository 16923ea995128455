"""Stability of the isothermal and adiabatic splits (Armero & Simo 1992) on a
thermoelastic bar with an artificially strong coupling (doc/thermal.md,
"Stability of the splits").

An insulated plane-strain block (Table 1 material of the seed, hypoelastic,
T0 = 300 K) is pulled by a traction s on its right face in the first step and
then held. Everything is homogeneous, so each scheme reduces to the one-dof
recursions derived in doc/thermal.md. With the heat capacity at constant volume
(the seed's c_v, eq. 8: the thermoelastic heat comes from all of tr D):

  isothermal split:  d_n = -tau_v r d_{n-1},  d_n = T_{n+1} - T_n,
  adiabatic split:   d_n = 0 after the loading step (it is the monolithic answer),

with tau_v = 9 K beta^2 T0 / (rho c_v) and r = 2(1 + nu)/3 the share of the
free thermal volume change in plane strain. The isothermal split is stable only
for tau_v r < 1; the adiabatic split for every tau. The loading step's
temperature is the root of
  rho c_v th = -3 K beta (T0 + th) ((1 + nu) s/(3K) + 2 (1 + nu) beta th).
With the heat capacity at constant stress (c_p = c_v + 9 K beta^2 T0 / rho,
the same material) the isothermal split's recursion is d_n = tau_p (1 - r)
d_{n-1}, tau_p = tau_v / (1 + tau_v) < 1: stable, converging to the same
temperature. The test measures the amplification factors and asserts them
against these predictions, and the temperatures against the closed form.
"""
import math

from anvil_test import run, read_csv, check, close, finish

K, nu, rho, c_v, T0, s = 70000.0, 0.3, 2.7e-9, 0.9e9, 300.0, 10.0
E = 3 * K * (1 - 2 * nu)
r = 2 * (1 + nu) / 3
dt, steps = 0.1, 12


def beta_for(tau_v):
    return math.sqrt(tau_v * rho * c_v / (9 * K * T0))


def simulate(name, coupling, beta, convention="constant volume", c=c_v):
    sets = ["Physics/Coupling=" + coupling,
            "Heat/Initial temperature=%g" % T0,
            "Geometry/Random distortion=0",
            "Bodies/body/Material/Model=hypoelastic",
            "Bodies/body/Material/Elasticity/Young's modulus=0",
            "Bodies/body/Material/Elasticity/Bulk modulus=%g" % K,
            "Bodies/body/Material/Elasticity/Poisson's ratio=%g" % nu,
            "Bodies/body/Material/Elasticity/Density=%g" % rho,
            "Bodies/body/Material/Elasticity/Heat capacity=%.15g" % c,
            "Bodies/body/Material/Elasticity/Heat capacity at=" + convention,
            "Bodies/body/Material/Elasticity/Thermal expansion=%.15g" % beta,
            "Bodies/body/Material/Elasticity/Reference temperature=%g" % T0,
            "Boundary conditions/Displacement=left: ux = 0; bottom: uy = 0",
            "Boundary conditions/Pressure=right: -%g" % s,
            "Heat/Time integration/Relative tolerance=1e-10",
            "Heat/Time integration/Absolute tolerance=1e-10",
            "Mechanics/Newton/Residual tolerance=1e-11",
            "Mechanics/Newton/Absolute residual tolerance=1e-9",
            "Time/Time step=%g" % dt, "Time/End time=%g" % (dt * steps),
            "Time/Growth factor=1", "Time/Maximum time step=%g" % dt,
            "Output/Probes=c: 0.5, 0.5",
            "Output/Quantities of interest=T: mean(temperature)"]
    out, summary, _ = run("tests/homogeneous.prm", sets, name="split_stability_" + name)
    T = read_csv(out + "/probes.csv")["c_temperature"]
    d = [T[n + 1] - T[n] for n in range(len(T) - 1)]
    return T, d, summary


def adiabatic_temperature(beta, c):
    """Root of rho c th + 3 K beta (T0 + th)((1 + nu) s/(3K) + 2 (1 + nu) beta th) = 0 (c_v)."""
    a = 3 * K * beta * 2 * (1 + nu) * beta
    b = rho * c + 3 * K * beta * ((1 + nu) * s / (3 * K) + 2 * (1 + nu) * beta * T0)
    cc = 3 * K * beta * T0 * (1 + nu) * s / (3 * K)
    return (-b + math.sqrt(b * b - 4 * a * cc)) / (2 * a)


def amplification(d, first=2, last=6):
    return [d[n] / d[n - 1] for n in range(first, last + 1)]


print("plane-strain bar, r = 2(1 + nu)/3 = %.4f: the isothermal split (c_v) is stable for tau_v < 1/r = %.4f"
      % (r, 1 / r))
results = {}
for tau_r in (0.7, 1.5):
    tau_v = tau_r / r
    beta = beta_for(tau_v)
    T, d, _ = simulate("isothermal_%g" % tau_r, "isothermal split", beta)
    g = amplification(d)
    print("isothermal split, tau_v = %.4f (tau_v r = %.2f, beta = %.4g /K): T = %s"
          % (tau_v, tau_r, beta, " ".join("%.5f" % x for x in T[:8])))
    print("  amplification d_n/d_(n-1), steps 2-6: %s; predicted %.4f" % (" ".join("%.4f" % x for x in g), -tau_r))
    for x in g:
        close(x, -tau_r, 0.03, "isothermal split amplification at tau_v r = %.2f" % tau_r)
    growth = abs(d[-1] / d[1])
    if tau_r > 1:
        check(growth > 50, "isothermal split diverges at tau_v r = %.2f: |d| grew %.3g times in %d steps"
              % (tau_r, growth, len(d) - 2))
    else:
        check(growth < 0.05, "isothermal split is stable at tau_v r = %.2f: |d| shrank to %.3g"
              % (tau_r, growth))

for tau_r in (1.5, 10.0):
    tau_v = tau_r / r
    beta = beta_for(tau_v)
    T, d, summary = simulate("adiabatic_%g" % tau_r, "adiabatic split", beta)
    expected = adiabatic_temperature(beta, c_v)
    drift = max(abs(x - T[1]) for x in T[1:])
    newton = summary["newton_iterations"] / summary["steps"]
    print("adiabatic split, tau_v r = %.2f: T = %s, closed form T0 + %.8f, Newton %.2f per step"
          % (tau_r, " ".join("%.6f" % x for x in T[:5]), expected, newton))
    # The closed form is small-strain: finite-strain terms are O(strain) ~ 1e-4.
    close(T[1] - T0, expected, 1e-4, "adiabatic split: loading-step temperature change (K), tau_v r = %g" % tau_r)
    check(drift < 1e-7 * abs(expected),
          "adiabatic split is stable at tau_v r = %g: T drifts by %.2g K after loading" % (tau_r, drift))
    check(newton <= 3, "coupled adiabatic tangent: %.2f Newton iterations per step at tau_v r = %g"
          % (newton, tau_r))
    results[tau_r] = expected

# The same material with c at constant stress: c_p = c_v + 9 K beta^2 T0 / rho.
tau_r = 1.5
tau_v = tau_r / r
beta = beta_for(tau_v)
c_p = c_v + 9 * K * beta * beta * T0 / rho
tau_p = tau_v / (1 + tau_v)
T, d, _ = simulate("isothermal_cp", "isothermal split", beta, "constant stress", c_p)
g = d[2] / d[1]
print("isothermal split, c at constant stress (tau_p = %.4f): T = %s; amplification %.4f, predicted tau_p (1 - r) = %.4f"
      % (tau_p, " ".join("%.6f" % x for x in T[:6]), g, tau_p * (1 - r)))
close(g, tau_p * (1 - r), 0.05, "isothermal split amplification with c_p")
# Same material: the converged temperature is the c_v adiabatic one to O(th/T0).
close(T[-1] - T0, results[1.5], 2e-3, "isothermal split with c_p converges to the c_v monolithic temperature change (K)")
finish()

"""Prescribed temperature (Physics/Coupling = prescribed temperature): T(x, t)
given, no heat equation solved; the mechanics must follow it within the step.

Independent answers:
1. A free unit cube (hypoelastic, beta) under T = 293 + 100 t expands by
   D = beta dT/dt I, i.e. ln(lambda) = beta (T - T0): each edge grows by
   exp(beta dT) - 1 (the linear beta dT is 5e-4 relative away: the test sees
   finite strain). With a one-step lag it would see dT(t - dt): 10 % less.
2. A perfectly plastic cube pulled in uniaxial stress while T ramps: the
   Cauchy stress equals the softened yield stress sigma0 (1 - omega (T(t) -
   T_ref)) (seed eq. 35) at every plastic step, at T of that step (a lag
   would leave it sigma0 omega 100 dt = 6 MPa high).
3. The scene builds no heat problem (no Heat timers, no thermal.csv), and a
   heat boundary condition section is simply not read.
"""
import math
import os

from anvil_test import run, read_csv, check, close, finish

# 1. Free thermal expansion, 3D.
beta = 1e-5
out, s, _ = run("tests/prescribed_block.prm",
                ["Bodies/body/Material/Model=hypoelastic",
                 "Bodies/body/Material/Elasticity/Thermal expansion=%g" % beta,
                 "Boundary conditions/Displacement=left: ux = 0; bottom: uy = 0; front: uz = 0",
                 "Mechanics/Newton/Absolute residual tolerance=1e-12",
                 "Output/Probes=corner: 1, 1, 1"],
                name="prescribed_expansion")
probes = read_csv(os.path.join(out, "probes.csv"))
worst = 0.0
for t, ux, uy, uz in zip(probes["time"], probes["corner_ux"], probes["corner_uy"], probes["corner_uz"]):
    expected = math.expm1(beta * 100 * t)
    for u in (ux, uy, uz):
        worst = max(worst, abs(u - expected) / max(expected, 1e-300) if t > 0 else abs(u))
print("  free cube: corner displacement at t = 1: %.12e mm, exp(beta dT) - 1 = %.12e mm"
      % (probes["corner_ux"][-1], math.expm1(beta * 100)))
check(worst < 1e-7, "every step: edge stretch exp(beta (T(t) - T0)) - 1 to %.1e (tolerance 1e-7)" % worst)
check(abs(probes["corner_ux"][-1] - beta * 100) / (beta * 100) > 1e-4,
      "the answer is the finite-strain one, not the linear beta dT (differs by %.1e)"
      % (abs(probes["corner_ux"][-1] - beta * 100) / (beta * 100)))
heat_timers = [k for k in s["wall_time_per_phase"] if k.startswith("Heat")]
check(s["coupling"] == "prescribed temperature" and not heat_timers and "temperature_dofs" not in s
      and not os.path.exists(os.path.join(out, "thermal.csv")),
      "no heat problem built: no Heat timers, no temperature DoFs, no thermal.csv")

# 2. Temperature-dependent yield follows T(t) with no lag.
sigma0, omega = 300.0, 2e-3
out, s, _ = run("tests/prescribed_block.prm",
                ["Output/Quantities of interest=T: mean(temperature)"],
                name="prescribed_softening")
probes = read_csv(os.path.join(out, "probes.csv"))
worst, n_plastic = 0.0, 0
for t, szz, p in zip(probes["time"], probes["centre_stress_zz"], probes["centre_equivalent_plastic_strain"]):
    if p <= 0:
        continue
    n_plastic += 1
    expected = sigma0 * (1 - omega * 100 * t)
    worst = max(worst, abs(szz - expected) / expected)
    print("  t = %.2f s: sigma_zz = %.9f MPa, sigma0 (1 - omega (T(t) - T_ref)) = %.9f MPa" % (t, szz, expected))
check(n_plastic >= 7, "the cube yields from the second step on (%d plastic steps)" % n_plastic)
check(worst < 1e-9, "stress = softened yield stress at T of the same step, to %.1e (tolerance 1e-9)" % worst)
close(s["quantities_of_interest"]["T"], 393.0, 1e-12, "mean(temperature) at t = 1 (293 + 100 t)")

# 3. The expression is checked before any work.
import subprocess
from anvil_test import ANVIL, SOURCE_DIR
p = subprocess.run([ANVIL, os.path.join(SOURCE_DIR, "tests/prescribed_block.prm"),
                    "--set", "Physics/Prescribed temperature=293 + q*t"], capture_output=True, text=True)
check(p.returncode == 2 and "Prescribed temperature" in p.stderr and len(p.stderr.strip().splitlines()) == 1,
      "a bad expression: one line naming Physics/Prescribed temperature, exit 2 (%r)" % p.stderr.strip())
finish()

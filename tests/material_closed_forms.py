"""Material points against closed forms (seed sec. 1.3, 1.4, 2.3), driven by
anvil --material-point along uniaxial paths (exx or sxx prescribed, every other
stress component zero):

 1. J2, linear hardening: sigma = E eps below yield, then
    sigma = s0 + E h/(E + h) (eps - s0/E); the plastic strain is eps - sigma/E;
 2. J2, Voce hardening: sigma = s_v(p) with p = eps - sigma/E on every step;
 3. Perzyna (n = 1, m = 1, h = 0) at constant strain rate: after yield
    sigma = s0 + eta epsdot (1 - exp(-(t - t_y) E/eta)); steady overstress
    eta epsdot^(1/m) also for m = 2 and 5;
 4. Perzyna relaxation at fixed strain: sigma - s0 decays as exp(-t E/eta);
 5. Perzyna creep at fixed stress: constant creep rate ((sigma - s0)/eta)^m;
 6. eta -> 0 reproduces rate-independent J2 to 1e-10;
 7. adiabatic plastic heating: rho c dT = chi int sigma dp (linear hardening:
    chi (s0 p + h p^2/2));
 8. Kelvin's thermoelastic cooling in adiabatic uniaxial tension:
    dT = -beta T dsigma/(rho c), i.e. T = T0 exp(-beta dsigma/(rho c)); the
    Table 1 material gives -0.2946 K per 100 MPa at 300 K;
 9. objectivity: a plastically prestressed point rotated rigidly by 90 degrees
    keeps its stress, co-rotated (1e-10).
Time-discretisation errors of the viscous paths are checked by their
observed order (backward Euler: 1)."""
import math
import os

from anvil_test import SOURCE_DIR, read_csv, check, close, finish, run_point

J2 = os.path.join(SOURCE_DIR, "tests", "material", "j2_uniaxial.prm")
E, nu, s0, h = 200000.0, 0.3, 300.0, 1000.0


def last(c, k):
    return c[k][-1]


# ------------------------------------------------------------------ 1. linear
c = read_csv(run_point(J2, name="j2_linear")[0])
worst = 0
for eps, sig, p in zip(c["exx"], c["sxx"], c["equivalent_plastic_strain"]):
    exact = E * eps if eps <= s0 / E else s0 + E * h / (E + h) * (eps - s0 / E)
    worst = max(worst, abs(sig - exact) / max(abs(exact), 1.0), abs(p - max(eps - sig / E, 0)))
print("  J2 linear: final sxx %.6f (closed form %.6f)" % (last(c, "sxx"), s0 + E * h / (E + h) * (0.02 - s0 / E)))
check(worst < 1e-10, "J2 linear hardening, uniaxial stress: worst relative error %.2e over 200 steps" % worst)
check(max(abs(x) for x in c["syy"] + c["szz"]) < 1e-8, "lateral stresses vanish")

# ------------------------------------------------------------------ 2. Voce
c = read_csv(run_point(J2, ["Material/Hardening/Model=voce"], name="j2_voce")[0])
worst = 0
for eps, sig, p in zip(c["exx"], c["sxx"], c["equivalent_plastic_strain"]):
    if p > 0:
        sv = s0 + (500 - s0) * (1 - math.exp(-20 * p))
        worst = max(worst, abs(sig - sv) / sv, abs(p - (eps - sig / E)))
print("  Voce: final sxx %.6f at p = %.6f" % (last(c, "sxx"), last(c, "equivalent_plastic_strain")))
check(worst < 1e-10, "J2 Voce hardening: sigma = s_v(p) and p = eps - sigma/E, worst error %.2e" % worst)

# ------------------------------------------------------------------ 3. Perzyna, constant strain rate
eta, rate = 1000.0, 0.02
perz = ["Material/Model=Perzyna", "Material/Hardening/Hardening modulus=0"]
tau, t_y = eta / E, s0 / (E * rate)
errors = []
for steps in (2000, 4000):
    c = read_csv(run_point(J2, perz + ["Path/Steps=%d" % steps], name="perzyna_rate_%d" % steps)[0])
    err = 0
    for t, sig in zip(c["time"], c["sxx"]):
        exact = E * rate * t if t <= t_y else s0 + eta * rate * (1 - math.exp(-(t - t_y) / tau))
        err = max(err, abs(sig - exact))
    errors.append(err)
    print("  Perzyna m=1, %d steps: final overstress %.10f MPa (eta epsdot = %.1f), max error %.3e MPa"
          % (steps, last(c, "sxx") - s0, eta * rate, err))
close(last(c, "sxx") - s0, eta * rate, 1e-9, "Perzyna steady overstress eta*epsdot")
order = math.log(errors[0] / errors[1], 2)
check(0.8 < order < 1.2, "Perzyna transient: backward-Euler order %.3f (expected 1)" % order)
for m in (2, 5):
    c = read_csv(run_point(J2, perz + ["Material/Viscosity/m/Value=%d" % m], name="perzyna_m%d" % m)[0])
    close(last(c, "sxx") - s0, eta * rate ** (1.0 / m), 1e-8, "Perzyna m=%d steady overstress eta*epsdot^(1/m)" % m)

# ------------------------------------------------------------------ 4. relaxation
# exx jumps to 0.005 in the first step (dt = 1e-5 s), then is held.
errors = []
for steps in (1000, 2000):
    dt = 0.05 / steps
    c = read_csv(run_point(J2, perz + ["Path/End time=0.05", "Path/Steps=%d" % steps,
                                       "Path/Strain=exx: 0.005*min(t/%g, 1)" % dt], name="relax_%d" % steps)[0])
    t1, d1 = c["time"][1], c["sxx"][1] - s0
    err = 0
    for t, sig in zip(c["time"][1:], c["sxx"][1:]):
        err = max(err, abs((sig - s0) - d1 * math.exp(-(t - t1) / tau)) / d1)
    errors.append(err)
    print("  relaxation, %d steps: overstress %.4f -> %.3e MPa over %.0f tau, max error %.3e of the initial overstress"
          % (steps, d1, last(c, "sxx") - s0, (0.05 - t1) / tau, err))
check(errors[1] < 1e-2, "relaxation follows exp(-t E/eta) (max error %.2e)" % errors[1])
order = math.log(errors[0] / errors[1], 2)
check(0.8 < order < 1.2, "relaxation: backward-Euler order %.3f (expected 1)" % order)

# ------------------------------------------------------------------ 5. creep
m, sigma = 2, 350.0
c = read_csv(run_point(J2, perz + ["Material/Viscosity/m/Value=%d" % m, "Path/Steps=100",
                                   "Path/Strain=", "Path/Stress=sxx: %g*min(t/0.01, 1)" % sigma],
                       name="creep")[0])
creep_rate = ((sigma - s0) / eta) ** m
rates = [(c["exx"][k + 1] - c["exx"][k]) / (c["time"][k + 1] - c["time"][k]) for k in range(5, len(c["time"]) - 1)]
print("  creep at %g MPa: strain rate %.12g /s, closed form ((s - s0)/eta)^m = %.12g /s" % (sigma, rates[-1], creep_rate))
check(max(abs(r - creep_rate) for r in rates) < 1e-9 * creep_rate, "creep at fixed stress: constant rate ((s - s0)/eta)^m")

# ------------------------------------------------------------------ 6. eta -> 0
cyc = ["Path/Strain=exx: 0.01*sin(2*pi*t)", "Path/Steps=100"]
a = read_csv(run_point(J2, cyc, name="j2_cyclic")[0])
b = read_csv(run_point(J2, cyc + ["Material/Model=Perzyna", "Material/Viscosity/Eta/Value=1e-12"], name="perzyna_eta0")[0])
diff = max(abs(x - y) for x, y in zip(a["sxx"], b["sxx"])) / max(abs(x) for x in a["sxx"])
check(diff < 1e-10, "eta = 1e-12 reproduces rate-independent J2 on a tension-compression cycle (max difference %.2e)" % diff)
b = read_csv(run_point(J2, cyc + ["Material/Model=Perzyna", "Material/Viscosity/Eta/Value=0"], name="perzyna_eta_zero")[0])
diff = max(abs(x - y) for x, y in zip(a["sxx"], b["sxx"])) / max(abs(x) for x in a["sxx"])
check(diff == 0, "eta = 0 is rate-independent J2 exactly (max difference %.2e)" % diff)

# ------------------------------------------------------------------ 7. adiabatic plastic heating
chi, rho, cap = 0.9, 7.8e-9, 4.6e8
c = read_csv(run_point(J2, ["Path/Adiabatic=true", "Path/Strain=exx: 0.2*t"], name="adiabatic_heating")[0])
p = last(c, "equivalent_plastic_strain")
dT = last(c, "temperature") - 293
exact = chi * (s0 * p + h * p * p / 2) / (rho * cap)
print("  adiabatic heating: p = %.6f, dT = %.8f K, chi (s0 p + h p^2/2)/(rho c) = %.8f K" % (p, dT, exact))
close(dT, exact, 1e-9, "adiabatic plastic heating rho c dT = chi int sigma dp")

# ------------------------------------------------------------------ 8. Kelvin
kelvin = ["Material/Model=hypoelastic", "Material/Elasticity/Young's modulus=0",
          "Material/Elasticity/Bulk modulus=70000", "Material/Elasticity/Density=2.7e-9",
          "Material/Elasticity/Heat capacity=0.9e9", "Material/Elasticity/Thermal expansion=23.86e-6",
          "Material/Elasticity/Reference temperature=300", "Path/Temperature=300", "Path/Adiabatic=true",
          "Path/Strain=", "Path/Stress=sxx: 100*t"]
errors = []
for steps in (100, 200):
    c = read_csv(run_point(J2, kelvin + ["Path/Steps=%d" % steps], name="kelvin_%d" % steps)[0])
    dT = last(c, "temperature") - 300
    exact = 300 * (math.exp(-23.86e-6 * 100 / (2.7e-9 * 0.9e9)) - 1)
    errors.append(abs(dT - exact))
    print("  Kelvin, %d steps: dT = %.7f K for +100 MPa at 300 K (-beta T dsigma/(rho c) = %.7f K, exact %.7f K)"
          % (steps, dT, -23.86e-6 * 300 * 100 / 2.43, exact))
close(dT, exact, 1e-5, "Kelvin's thermoelastic cooling")
# The reference -0.2946 K is the linearised formula at 300 K; the exact
# integral differs by the second-order term beta dsigma/(2 rho c) = 4.9e-4.
lin = -23.86e-6 * 300 * 100 / 2.43
check(abs(round(lin, 4) + 0.2946) < 1e-12 and abs(dT - lin) < 5e-4 * abs(lin),
      "Kelvin: %.5f K against the reference -0.2946 K (linearised), within the second-order term" % dT)

# ------------------------------------------------------------------ 9. objectivity with plastic prestress
F = ("Path/Deformation gradient=F11: cos(pi/2*max(2*t-1,0))*(1+0.004*min(2*t,1)); "
     "F12: -sin(pi/2*max(2*t-1,0)); F21: sin(pi/2*max(2*t-1,0))*(1+0.004*min(2*t,1)); "
     "F22: cos(pi/2*max(2*t-1,0))")
c = read_csv(run_point(J2, ["Path/Control=deformation gradient", F, "Path/Steps=100"], name="j2_rotation")[0])
mid = len(c["time"]) // 2
check(c["equivalent_plastic_strain"][mid] > 0, "the point is plastic before the rotation (p = %.2e)" % c["equivalent_plastic_strain"][mid])
scale = abs(c["sxx"][mid])
for a_, b_ in (("sxx", "syy"), ("syy", "sxx"), ("szz", "szz")):
    close(last(c, a_), c[b_][mid], 1e-10, "after 90 degrees %s = %s before" % (a_, b_), atol=1e-10 * scale)
check(abs(last(c, "sxy")) < 1e-10 * scale, "no spurious shear after the rotation (%.2e)" % last(c, "sxy"))
finish()

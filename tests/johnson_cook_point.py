"""Johnson-Cook (issue 16) on one material point in uniaxial stress, driven
at a constant axial strain rate and a constant temperature (strain control,
every other stress component zero), against the closed form

    sigma_y = (A + B e^n) (1 + C ln(e_dot / e_dot_0)) (1 - T*^m),
    T* = (T - T_tr) / (T_m - T_tr), the rate factor 1 for e_dot <= e_dot_0,

 1. at every plastic step, von Mises = sigma_y at the step's plastic strain e
    and plastic rate e_dot = de/dt (what the return map must satisfy), and
    sxx = E (exx - e) (uniaxial: the plastic axial strain is e);
 2. at the end (e ~ 0.5), von Mises against the closed form at the
    *prescribed* strain rate: the plastic rate there differs from it only
    by the elastic rate (d sigma/dt)/E: to 1e-4 (measured 3e-5);
 3. rate and temperature scaling: at equal plastic strain, the stresses of
    two rates differ by the factor (1 + C ln r1)/(1 + C ln r2); below the
    reference rate the factor is 1; at T = 700 K by (1 - T*^m);
 4. the hardening law A + B e^n (J2, Hardening/Model = johnson-cook with
    Johnson-Cook thermal softening) follows the closed form without the
    rate factor;
 5. bad Johnson-Cook input: exit 2, one line naming the entry.
"""
import math
import os

from anvil_test import SOURCE_DIR, WORK_DIR, read_csv, check, close, finish, run_point

OUT = os.path.join(WORK_DIR, "output", "johnson_cook_point")
os.makedirs(OUT, exist_ok=True)

E, nu = 124000.0, 0.34
A, B, n, C, rate0, m, Tm, Ttr = 90.0, 292.0, 0.31, 0.025, 1.0, 1.09, 1356.0, 293.0
STRAIN = 0.5


def theta(T):
    s = min(max((T - Ttr) / (Tm - Ttr), 0.0), 1.0)
    return 1 - s ** m


def closed_form(e, rate, T, rate_factor=True):
    r = 1 + C * math.log(rate / rate0) if rate_factor and rate > rate0 else 1.0
    return (A + B * e ** n) * r * theta(T)


def write(name, material, rate, T, steps=500):
    prm = os.path.join(OUT, name + ".prm")
    with open(prm, "w") as f:
        f.write(material)
        f.write("subsection Path\n  set Control = strain\n  set End time = %.17g\n  set Steps = %d\n"
                "  set Strain = exx: %.17g*t\n  set Temperature = %.17g\nend\n"
                % (STRAIN / rate, steps, rate, T))
    return prm


elastic = ("  subsection Elasticity\n    set Young's modulus = %g\n    set Poisson's ratio = %g\n"
           "    set Thermal expansion = 0\n    set Reference temperature = 293\n  end\n" % (E, nu))
jc_model = ("subsection Material\n  set Model = Johnson-Cook\n" + elastic +
            "  subsection Johnson-Cook\n    set A = %g\n    set B = %g\n    set n = %g\n    set C = %g\n"
            "    set Reference strain rate = %g\n    set m = %g\n    set Melting temperature = %g\n"
            "    set Transition temperature = %g\n  end\nend\n" % (A, B, n, C, rate0, m, Tm, Ttr))
jc_hardening = ("subsection Material\n  set Model = J2\n" + elastic +
                "  subsection Hardening\n    set Model = johnson-cook\n    set Initial yield stress = %g\n"
                "    set Strength coefficient = %g\n    set Hardening exponent = %g\n"
                "    subsection Thermal softening\n      set Model = johnson-cook\n"
                "      set Melting temperature = %g\n      set Exponent = %g\n"
                "      set Reference temperature = %g\n    end\n  end\nend\n" % (A, B, n, Tm, m, Ttr))


def drive(name, material, rate, T, rate_factor=True):
    path, out, _ = run_point(write(name, material, rate, T), name=name)
    h = read_csv(path)
    worst_yield = worst_elastic = 0.0
    plastic = 0
    for i in range(1, len(h["step"])):
        e, e_old = h["equivalent_plastic_strain"][i], h["equivalent_plastic_strain"][i - 1]
        if e <= e_old:
            continue
        plastic += 1
        dt = h["time"][i] - h["time"][i - 1]
        expected = closed_form(e, (e - e_old) / dt, T, rate_factor)
        worst_yield = max(worst_yield, abs(h["von_mises"][i] - expected) / expected)
        worst_elastic = max(worst_elastic, abs(h["sxx"][i] - E * (h["exx"][i] - e)) / abs(h["sxx"][i]))
    e_end = h["equivalent_plastic_strain"][-1]
    final = closed_form(e_end, rate, T, rate_factor)
    print("  %-28s rate %8g /s, T = %5g K: %d plastic steps, e = %.5f, von Mises %.6f MPa, "
          "closed form at the prescribed rate %.6f MPa" % (name, rate, T, plastic, e_end, h["von_mises"][-1], final))
    check(plastic > 450, "%s: plastic from the first steps (%d of 500)" % (name, plastic))
    check(worst_yield < 1e-9, "%s: von Mises = closed form at each step's plastic strain and rate, worst %.2e (1e-9)"
          % (name, worst_yield))
    check(worst_elastic < 1e-9, "%s: sxx = E (exx - e), worst %.2e (1e-9)" % (name, worst_elastic))
    close(h["von_mises"][-1], final, 1e-4, "%s: final von Mises against the closed form at the prescribed rate" % name)
    return h


fast = drive("jc_rate_1e3", jc_model, 1e3, 293.0)
slow = drive("jc_rate_10", jc_model, 10.0, 293.0)
below = drive("jc_rate_0.1", jc_model, 0.1, 293.0)
hot = drive("jc_rate_1e3_700K", jc_model, 1e3, 700.0)
law = drive("j2_jc_hardening_700K", jc_hardening, 1e3, 700.0, rate_factor=False)


def at_strain(h, e):
    """von Mises at plastic strain e (linear between rows)."""
    x, y = h["equivalent_plastic_strain"], h["von_mises"]
    for i in range(1, len(x)):
        if x[i - 1] <= e <= x[i] and x[i] > x[i - 1]:
            w = (e - x[i - 1]) / (x[i] - x[i - 1])
            return (1 - w) * y[i - 1] + w * y[i]
    raise SystemExit("plastic strain %g not reached" % e)


e = 0.3
close(at_strain(fast, e) / at_strain(slow, e), (1 + C * math.log(1e3)) / (1 + C * math.log(10.0)), 2e-4,
      "rate scaling at e = 0.3: sigma(1e3 /s) / sigma(10 /s)")
close(at_strain(below, e), A + B * e ** n, 2e-4, "below the reference rate the factor is 1: sigma(0.1 /s) at e = 0.3")
close(at_strain(hot, e) / at_strain(fast, e), theta(700.0), 2e-4, "temperature scaling at e = 0.3: 1 - T*^m at 700 K")
close(at_strain(law, e), (A + B * e ** n) * theta(700.0), 2e-4, "hardening law A + B e^n with softening at e = 0.3, 700 K")

# ------------------------------------------------------------ bad input
for what, sets, entry in [("T_m below T_tr", ["Material/Johnson-Cook/Melting temperature=250"], "Melting temperature"),
                          ("negative C", ["Material/Johnson-Cook/C=-0.1"], "'Material/Johnson-Cook/C'"),
                          ("zero reference rate", ["Material/Johnson-Cook/Reference strain rate=0"], "Reference strain rate")]:
    path, out, err = run_point(write("bad", jc_model, 1e3, 293.0), sets, name="bad", expect_status=2)
    lines = [l for l in err.splitlines() if l.strip()]
    check(len(lines) == 1 and entry in lines[0] and "--set" in lines[0] and not os.path.exists(path),
          "bad input, %s: exit 2, one line: %s" % (what, " | ".join(lines)))
finish()

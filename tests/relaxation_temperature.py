"""Uniaxial stress relaxation of a Perzyna point at several temperatures with
temperature-dependent data (issue 13): E(T) (modulus factor table), sigma_0(T)
(hardening 'temperature linear', h = 0), eta(T), n(T), m(T) tables, held at
a constant temperature; the first step jumps exx to 0.005, then it is held.

Closed form (seed eq. 14, 18, uniaxial stress, h = 0): with the overstress
s = sigma - sigma_0(T) and c = eta(T)^(1/n(T)), the flow rule gives
epsdot_p = (s/c)^m and sigma = E(T) (exx - eps_p), so ds/dt = -E (s/c)^m:

  m = 1:  s(t) = s1 exp(-E (t - t1)/c)
  m != 1: s(t) = (s1^(1-m) + (m - 1) E (t - t1) / c^m)^(1/(1-m))

(s1 the overstress after the jump, at t1): the stress relaxes to the static
yield stress sigma_0(T) (eq. 18: sigma -> sigma_v(T)). Backward Euler: error
of first order in the step, checked by its observed order."""
import math
import os

from anvil_test import SOURCE_DIR, read_csv, check, finish, run_point

PRM = os.path.join(SOURCE_DIR, "tests", "material", "j2_uniaxial.prm")
E0 = 200000.0
# (T : value) tables; 400 K lies between nodes (interpolated data).
g_table = {293: 1.0, 493: 0.85, 693: 0.7}
s0_table = {293: 300.0, 493: 150.0, 693: 60.0}
eta_table = {293: 3000.0, 493: 800.0, 693: 200.0}
n_table = {293: 1.0, 493: 1.2, 693: 1.5}
m_table = {293: 1.0, 493: 2.0, 693: 3.0}


def table_text(t):
    return ", ".join("%g : %g" % (T, v) for T, v in sorted(t.items()))


def interp(t, T):
    xs = sorted(t)
    for a, b in zip(xs, xs[1:]):
        if a <= T <= b:
            return t[a] + (t[b] - t[a]) * (T - a) / (b - a)
    raise ValueError(T)


def closed_form(s1, E, c, m, dt):
    if m == 1:
        return s1 * math.exp(-E * dt / c)
    return (s1 ** (1 - m) + (m - 1) * E * dt / c ** m) ** (1 / (1 - m))


sets = ["Material/Model=Perzyna",
        "Material/Elasticity/Modulus temperature factor/Model=table",
        "Material/Elasticity/Modulus temperature factor/Table=" + table_text(g_table),
        "Material/Hardening/Model=temperature linear",
        "Material/Hardening/Yield stress of T/Model=table",
        "Material/Hardening/Yield stress of T/Table=" + table_text(s0_table),
        "Material/Viscosity/Eta/Model=table", "Material/Viscosity/Eta/Table=" + table_text(eta_table),
        "Material/Viscosity/n/Model=table", "Material/Viscosity/n/Table=" + table_text(n_table),
        "Material/Viscosity/m/Model=table", "Material/Viscosity/m/Table=" + table_text(m_table)]



def relax(T, end, steps):
    dt = end / steps
    return read_csv(run_point(PRM, sets + ["Path/Temperature=%g" % T, "Path/End time=%g" % end,
                                           "Path/Steps=%d" % steps,
                                           "Path/Strain=exx: 0.005*min(t/%g, 1)" % dt],
                              name="relax_T%d_%d" % (T, steps))[0])


def initial_time_scale(s1, E, c, m):
    """s/|ds/dt| at the start: c^m / (E s1^(m-1))."""
    return c ** m / (E * s1 ** (m - 1))


for T in (293, 400, 493, 693):
    E, s0 = E0 * interp(g_table, T), interp(s0_table, T)
    m, c = interp(m_table, T), interp(eta_table, T) ** (1 / interp(n_table, T))
    # The window is 100/m initial time scales of the overstress after the
    # jump (measured by a first run): backward Euler's error grows with the
    # nonlinearity m, so every temperature is resolved alike.
    end = 1.0
    for _ in range(2):
        probe = relax(T, end, 1000)
        end = 100 / m * initial_time_scale(probe["sxx"][1] - s0, E, c, m)
    errors = []
    for steps in (2000, 4000):
        c_csv = relax(T, end, steps)
        t1, s1 = c_csv["time"][1], c_csv["sxx"][1] - s0
        err = max(abs((sig - s0) - closed_form(s1, E, c, m, t - t1)) / s1
                  for t, sig in zip(c_csv["time"][1:], c_csv["sxx"][1:]))
        errors.append(err)
    final = c_csv["sxx"][-1]
    expected = s0 + closed_form(s1, E, c, m, end - t1)
    print("  T = %d K, %.3g s: E %.0f, sigma_0 %.1f, c = eta^(1/n) %.2f, m %.2f: overstress %.3f -> %.4f MPa "
          "(closed form %.4f), max error %.2e / %.2e of s1 (2000 / 4000 steps)"
          % (T, end, E, s0, c, m, s1, final - s0, expected - s0, errors[0], errors[1]))
    check(errors[1] < 1e-2, "T = %d K: relaxation follows the closed form (max error %.2e of s1)" % (T, errors[1]))
    order = math.log(errors[0] / errors[1], 2)
    check(0.8 < order < 1.2, "T = %d K: backward-Euler order %.3f (expected 1)" % (T, order))
    check(final - s0 < 0.2 * s1, "T = %d K: the overstress relaxes toward sigma_v(T) = %.1f MPa (final sigma %.3f)"
          % (T, s0, final))
finish()

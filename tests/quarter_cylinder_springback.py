"""Springback of the quarter-cylinder forming (prm/quarter_cylinder_forming.prm,
seed sec. 4.1, issue 13) against the closed form of elastic-perfectly plastic
pure bending unloading (doc/quarter_cylinder_forming.md):

  kappa_e = 2 s'/(E' t), E' = E(T)/(1 - nu^2), s' = (2/sqrt 3) sigma_0(T),
  dkappa(kappa) = kappa_e (3/2 - (kappa_e/kappa)^2/2)  (kappa >= kappa_e),
                = kappa                               (kappa <  kappa_e),

each section unloading elastically to M = 0. Two forms:
- 'uniform' (printed): the sheet wrapped at the die's mid-surface curvature over its
  whole length, springback L dkappa(1/(R + t/2)) (the seed's statement);
- 'local' (checked): the same dkappa applied to the curvature the run has at the end of
  the hold, section by section (82 probes on the top and bottom faces, the
  rotation of each cross-section; kappa = -d theta/dx), summed to the free
  end: separates the closed form from the sheet not wrapping near its free
  end (the pressure's moment vanishes there).
Hot forming: after the 2700 s hold the Perzyna overstress has relaxed (seed
eq. 18, sigma -> sigma_v(T)), so the same forms hold with E(T) and the
relaxed stress of the forming temperature, if the sheet unloads at it: the
493 and 693 K runs hold the forming temperature during the unloading (the
scene cools while unloading: tabulated by the sweep, not checked). 293 K is
the scene as shipped. The relaxed stress is sigma_0(T) plus the overstress
the relaxation closed form leaves after 2700 s (2.4, 3.6, 4.7 % of sigma_0
at 293, 493, 693 K). Linear hardening adds < 0.2 % to M at these curvatures
(doc), not modelled. Tolerance 3.5 %: two Q2 cells through the thickness
integrate the kinked stress profile of M with 3 Gauss points each.

Then the seed's trend on the scene as shipped at 293, 493, 693, 993 K: the
springback decreases with the forming temperature. Label long (6 runs)."""
import math
import os

from anvil_test import run, read_csv, check, close, finish

L, R, t_sheet, nu, E0 = 25 * math.pi ** 2, 50 * math.pi, 1.0, 0.33, 70000.0
g_table = {293: 1, 493: 0.89, 693: 0.77, 793: 0.71, 993: 0.58}     # as in the scene
s0_table = {293: 145, 493: 90, 693: 15, 793: 5, 993: 1}
eta_table = {293: 10, 493: 60, 693: 300, 793: 300, 993: 30}
m_table = {293: 20, 493: 6.7, 693: 3.3, 793: 2, 993: 2}
HOLD = 2700.0
STATIONS = 40


def interp(table, T):
    xs = sorted(table)
    for a, b in zip(xs, xs[1:]):
        if a <= T <= b:
            return table[a] + (table[b] - table[a]) * (T - a) / (b - a)


def overstress_after_hold(T):
    """Perzyna overstress left after the hold (eq. 14 with n = 1 and 18):
    ds/dt = -E (s/eta)^m relaxes any start to at most
    s = ((m - 1) E t_hold / eta^m)^(-1/(m - 1)) (the limit of a large start)."""
    E, eta, m = E0 * interp(g_table, T), interp(eta_table, T), interp(m_table, T)
    return ((m - 1) * E * HOLD / eta ** m) ** (-1 / (m - 1))


def dkappa(kappa, T):
    Ep = E0 * interp(g_table, T) / (1 - nu ** 2)
    sigma_v = interp(s0_table, T) + overstress_after_hold(T)
    kappa_e = 2 * (2 / math.sqrt(3)) * sigma_v / (Ep * t_sheet)
    return kappa_e * (1.5 - 0.5 * (kappa_e / kappa) ** 2) if kappa >= kappa_e else kappa


def section_rotation(c, k, i):
    """Rotation (rad) of the cross-section at station k, row i."""
    dx = c["t%d_ux" % k][i] - c["b%d_ux" % k][i]
    dy = 1 + c["t%d_uy" % k][i] - c["b%d_uy" % k][i]
    return -math.atan2(dx, dy)


def temperature(T, unload_hot):
    hold = "1" if unload_hot else "if(t < 3000, 1, max(0, (3100 - t)/100))"
    return "293 + (%g - 293)*if(t < 300, t/300, %s)" % (T, hold)


def springback(T, unload_hot):
    xs = [L * k / STATIONS for k in range(STATIONS + 1)]
    probes = "; ".join("b%d: %.10g, 0; t%d: %.10g, 1" % (k, x, k, x) for k, x in enumerate(xs))
    out, s, _ = run("prm/quarter_cylinder_forming.prm",
                    ["Physics/Prescribed temperature=" + temperature(T, unload_hot),
                     "Output/Probes=" + probes, "Output/Field interval=0", "Output/Verbosity=quiet"],
                    name="quarter_cylinder_%d%s" % (T, "_hot_unload" if unload_hot else ""))
    c = read_csv(os.path.join(out, "probes.csv"))
    hold = max(i for i, t in enumerate(c["time"]) if t <= 3000 * (1 + 1e-12))
    theta = [section_rotation(c, k, hold) for k in range(STATIONS + 1)]
    measured = theta[0] - section_rotation(c, 0, len(c["time"]) - 1)
    uniform = L * dkappa(1 / (R + t_sheet / 2), T)
    local = sum(dkappa(max((theta[k] - theta[k + 1]) / (xs[k + 1] - xs[k]), 1e-12), T)
                * (xs[k + 1] - xs[k]) for k in range(STATIONS))
    print("  %g K%s: %d steps, %d Newton; free end at the end of the hold %.2f deg; springback "
          "%.3f deg, closed form uniform %.3f (ratio %.3f), local %.3f (ratio %.3f)"
          % (T, " (unloaded hot)" if unload_hot else "", s["steps"], s["newton_iterations"],
             math.degrees(theta[0]), math.degrees(measured), math.degrees(uniform),
             measured / uniform, math.degrees(local), measured / local))
    return measured, uniform, local


shipped = {}
for T, hot in ((293, False), (493, True), (693, True)):
    measured, uniform, local = springback(T, hot)
    if not hot:
        shipped[T] = measured
    close(math.degrees(measured), math.degrees(local), 0.035,
          "%g K: springback [deg] vs the closed form on the curvature at the end of the hold" % T)
    # The fully wrapped form is printed, not checked: near its free end the
    # sheet is not on the die (measured above: the local form accounts for it).

for T in (493, 693, 993):
    shipped[T] = springback(T, False)[0]
values = [math.degrees(shipped[T]) for T in sorted(shipped)]
check(all(a > b for a, b in zip(values, values[1:])),
      "as shipped, the springback decreases with the forming temperature: %s deg at 293, 493, 693, "
      "993 K" % ", ".join("%.2f" % v for v in values))
finish()

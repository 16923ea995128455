"""Generalized-alpha's algorithmic dissipation, the energy audit's own column
(`algorithmic_dissipation` of energy.csv, eq. A3 of doc/energy_audit.md),
against answers that do not use it:

 a. One Q1 element whose only free dof is the top's uy
    (tests/algorithmic_dissipation.prm): an oscillator with the closed-form
    k = E(1 - nu)/((1 + nu)(1 - 2 nu)) and m = rho h^2/3 (consistent mass,
    uniform strain). The scheme's own recurrence for that oscillator
    (Chung & Hulbert 1993, written out below in a few lines) gives
    the energy E_n = 1/2 m v_n^2 + 1/2 k u_n^2 at every step; the column must
    be E_0 - E_n at every step (rho_inf = 0, 0.5 and 0.8, omega dt = 1 and 0.5).
 b. The amplitude decay of the scheme's principal root: after the start-up,
    over whole discrete half-periods, the energy left (E_0 - D_n) falls by
    |lambda_1|^(2 k), lambda_1 the complex root of the characteristic
    polynomial of generalized-alpha at omega dt (Chung & Hulbert's spectral
    analysis; no recurrence): to 2 % of the energy lost (rho_inf = 0.5, 0).
 c. rho_inf = 1 (the trapezoidal member) dissipates nothing: |D| < 1e-12 E_0.
 d. A bar (tests/dynamics_bar.prm, 50 elements, its roughest mode, rho_inf =
    0.5): the work balance W_ext + K_0 - K - W_sigma - D closes to 1e-6 of
    the initial energy while D is > 10 % of it (without the column the
    balance would miss by D), and two processes give one process's D to 1e-8.
"""
import cmath
import math
from anvil_test import run, read_csv, check, close, finish

E, NU, RHO, H, V0 = 200000.0, 0.3, 7.8e-9, 1.0, 1.0
K = E * (1 - NU) / ((1 + NU) * (1 - 2 * NU))   # N/mm per mm of depth (strain u/h over h^2)
M = RHO * H * H / 3                              # consistent mass of the uniform mode
OMEGA = math.sqrt(K / M)


def parameters(rho):
    am = (2 * rho - 1) / (rho + 1)
    af = rho / (rho + 1)
    gamma = 0.5 - am + af
    beta = 0.25 * (1 - am + af) ** 2
    return am, af, gamma, beta


def recurrence(rho, dt, n):
    """Energies of the scheme's 1-dof solution, u0 = 0, v0 = V0, a0 = 0."""
    am, af, gamma, beta = parameters(rho)
    u, v, a = 0.0, V0, 0.0
    energies = [0.5 * M * v * v]
    for _ in range(n):
        # m((1-am) a1 + am a) + k((1-af) u1 + af u) = 0, u1 = u + dt v + dt^2((1/2-b) a + b a1)
        a1 = -(am * M * a + K * (af * u + (1 - af) * (u + dt * v + dt * dt * (0.5 - beta) * a))) \
            / ((1 - am) * M + (1 - af) * K * beta * dt * dt)
        u1 = u + dt * v + dt * dt * ((0.5 - beta) * a + beta * a1)
        v = v + dt * ((1 - gamma) * a + gamma * a1)
        u, a = u1, a1
        energies.append(0.5 * M * v * v + 0.5 * K * u * u)
    return energies


def principal_root(rho, w):
    """The complex root of p(l) = ((1-am) l + am)(l-1)^2 + w^2 ((1-af) l + af)
    ((1-g) + g l + (l-1)(1/2 - b + b l)), Durand-Kerner."""
    am, af, g, b = parameters(rho)
    p = lambda l: ((1 - am) * l + am) * (l - 1) ** 2 + \
        w * w * ((1 - af) * l + af) * ((1 - g + g * l) + (l - 1) * (0.5 - b + b * l))
    lead = (1 - am) + w * w * (1 - af) * b
    z = [complex(0.4, 0.9) ** k for k in range(3)]
    for _ in range(500):
        z = [zi - p(zi) / lead / math.prod(zi - zj for j, zj in enumerate(z) if j != i)
             for i, zi in enumerate(z)]
    return max(z, key=lambda r: abs(r.imag))


# a, b. The oscillator.
# (rho_inf, omega dt, whether the decay is checked against the root: at
# rho_inf = 0.8 the energy lost over a few periods, 0.2 %, is as small as the
# energy's own oscillation within a period, O((omega dt)^2) of the discrete
# mode's v/u ratio, so only the recurrence is compared there).
for rho, w, decay in ((0.5, 1.0, True), (0.5, 0.5, True), (0.0, 1.0, True), (0.8, 1.0, False)):
    dt = w / OMEGA
    root = principal_root(rho, w)
    half = math.pi / abs(cmath.phase(root))         # steps per discrete half-period
    start = 20
    n = start + round(4 * half)
    out, s, _ = run("tests/algorithmic_dissipation.prm",
                    ["Mechanics/Dynamics/Spectral radius=%g" % rho, "Time/Time step=%.17g" % dt,
                     "Time/End time=%.17g" % (n * dt)],
                    name="algorithmic_dissipation_rho%g_w%g" % (rho, w))
    e = read_csv(out + "/energy.csv")
    D = e["algorithmic_dissipation"]
    reference = recurrence(rho, dt, n)
    E0 = reference[0]
    close(s["energy"]["initial_kinetic_energy"], E0, 1e-12, "rho %g: K_0 = m v0^2 / 2" % rho)
    # energy.csv's rows are steps 0 (the initial state) to n.
    worst = max(abs(D[i] - (E0 - reference[i])) for i in range(n + 1)) / E0
    print("  rho_inf %g, omega dt %g: %d steps, D_end / E0 = %.6f (recurrence %.6f), worst step %.2e of E0"
          % (rho, w, len(D) - 1, D[-1] / E0, 1 - reference[-1] / E0, worst))
    check(len(D) == n + 1 and worst < 1e-6,
          "rho_inf %g, omega dt %g: D = E_0 - E_n of the scheme's recurrence at every step (%.2e of E0)"
          % (rho, w, worst))
    k = round(4 * half)
    ratio = (E0 - D[n]) / (E0 - D[start])
    predicted = abs(root) ** (2 * k)
    lost, lost_predicted = 1 - ratio, 1 - predicted
    print("  over %d steps (%.2f half-periods) from step %d: energy kept %.6f, |lambda_1|^2k = %.6f "
          "(|lambda_1| = %.7f), lost %.4e vs %.4e"
          % (k, k / half, start, ratio, predicted, abs(root), lost, lost_predicted))
    check(not decay or abs(lost - lost_predicted) < 0.02 * lost_predicted,
          "rho_inf %g, omega dt %g: energy lost over whole half-periods = 1 - |lambda_1|^2k to %.2f %%"
          % (rho, w, 100 * abs(lost / lost_predicted - 1)))

# c. rho_inf = 1 dissipates nothing.
out, s, _ = run("tests/algorithmic_dissipation.prm", ["Mechanics/Dynamics/Spectral radius=1",
                                                       "Time/Time step=%.17g" % (1 / OMEGA),
                                                       "Time/End time=%.17g" % (30.5 / OMEGA)],
                name="algorithmic_dissipation_rho1")
D = read_csv(out + "/energy.csv")["algorithmic_dissipation"]
E0 = s["energy"]["initial_kinetic_energy"]
check(max(abs(d) for d in D) < 1e-12 * E0, "rho_inf = 1: D = %.2e E_0" % (max(abs(d) for d in D) / E0))

# d. The bar's rough mode: the balance closes with D; np = 2 gives np = 1's D.
bar = {}
for np in (1, 2):
    out, s, _ = run("tests/dynamics_bar.prm", ["Mechanics/Dynamics/Initial velocity=ux = 1*cos(pi*x/2)",
                                               "Mechanics/Dynamics/Spectral radius=0.5",
                                               "Time/End time=1.6e-5"],
                    np=np, name="algorithmic_dissipation_bar_np%d" % np)
    bar[np] = (read_csv(out + "/energy.csv"), s)
e, s = bar[1]
K0 = s["energy"]["initial_kinetic_energy"]
D = e["algorithmic_dissipation"]
residual = [w + K0 - k - sw - d for w, k, sw, d in
            zip(e["external_work"], e["kinetic_energy"], e["stress_work"], D)]
worst = max(abs(r) for r in residual) / K0
print("  bar, rough mode, rho_inf 0.5: D_end = %.4e (%.1f %% of K_0), balance with D %.2e of K_0"
      % (D[-1], 100 * D[-1] / K0, worst))
check(D[-1] > 0.1 * K0 and worst < 1e-6,
      "bar: W_ext + K_0 - K - W_sigma - D = %.2e K_0 with D = %.3f K_0" % (worst, D[-1] / K0))
D2 = bar[2][0]["algorithmic_dissipation"]
deviation = max(abs(a - b) for a, b in zip(D, D2)) / K0
check(len(D2) == len(D) and deviation < 1e-8, "bar: np = 2 gives np = 1's D to %.2e of K_0" % deviation)
finish()

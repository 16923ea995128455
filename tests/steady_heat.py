"""Steady heat (Heat/Time integration/Method = steady, Heat/Initial temperature
field = steady) against closed forms, on prm/steady_slab.prm: a slab
0 < x < L held at T_D at x = 0, convection h and radiation (emissivity e) to
T_inf at x = L, a uniform source s, insulated top and bottom (1D). Exact:

    T(x) = T_D + a x - s x^2 / (2 k),   a = (T_L - T_D + s L^2 / (2 k)) / L,
    k (T_L - T_D) / L - s L / 2 = h (T_inf - T_L) + e sigma (T_inf^4 - T_L^4),

the last solved here for T_L by bisection (independently of anvil).

 a. With the source, on 10, 20, 40 cells: Q1 Galerkin in 1D is nodally exact
    (the error T - I T is Q1-orthogonal to the test functions' derivatives),
    so the nodal temperatures match to Newton's tolerance, and the error
    between nodes is that of the linear interpolant of the parabola: at each
    cell's midpoint exactly -s dx^2 / (8 k), order 2 under refinement.
    The heat balance of steady_heat.csv: the cold face's flow and the source
    are exact, the hot face's flow from k grad T . n is the first cell's
    secant, off by s dx H / 2: balance_error = s dx / (2 |q_cold|), order 1.
 b. Without the source the exact T is linear: every probe exact, balance
    error at round-off.
 c. Newton: contraction orders log(r_k+1/r_k)/log(r_k/r_k-1) of the printed
    residuals reach 2 (consistent tangent) with radiation, and with a
    temperature-dependent conductivity k = k0 (1 + b (T - T_ref)); without
    radiation and source (linear) one step solves it. With k(T) the closed
    form is the Kirchhoff transform theta = int k dT, theta'' = -s: T_L by
    bisection again. Q1 is nodally exact here too: k(T_h) T_h' = theta(T_h)'
    with theta(T_h) quadratic on a cell (k linear in T), which 2-point Gauss
    integrates exactly against the constant phi', so the discrete equations
    are the linear ones in the nodal theta.
 d. Loads in time (T_D = 1000 + 100 t): every step is the steady state of its
    end time.
 e. np = 1 and np = 2: the same temperatures and balance to 1e-10.
 f. A coupled scene (isothermal split, elastic slab) with Heat/Initial
    temperature field = steady starts from the thermal-only steady field
    (probes at t = 0), and, no heat being made, stays there under ARKode.
 g. Newton that cannot converge (Maximum iterations = 1): exit 3, with
    summary.json and the fields written.
"""
import math
import os
import re

from anvil_test import run, read_csv, check, close, finish

SCENE = "prm/steady_slab.prm"
SIGMA = 5.670374e-11
k, L, H = 1.0, 20.0, 2.0
T_D, s, h, T_inf, e = 1000.0, 0.5, 0.01, 293.0, 0.8


def bisect(g, lo=1.0, hi=5000.0):
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if g(mid) > 0:
            hi = mid
        else:
            lo = mid
    return 0.5 * (lo + hi)


def cold_flow(T):
    """Heat into the body per area at the cold face, mW/mm^2."""
    return h * (T_inf - T) + e * SIGMA * (T_inf ** 4 - T ** 4)


def exact_profile(T_D, s):
    T_L = bisect(lambda T: k * (T - T_D) / L - s * L / 2 - cold_flow(T))
    a = (T_L - T_D + s * L * L / (2 * k)) / L
    return T_L, (lambda x: T_D + a * x - s * x * x / (2 * k))


def probes(nx):
    """Probes at the nodes (n0..) and cell midpoints (m0..) of the mid-line."""
    dx = L / nx
    items = ["n%d: %.12g, 1" % (i, i * dx) for i in range(nx + 1)]
    items += ["m%d: %.12g, 1" % (i, (i + 0.5) * dx) for i in range(nx)]
    return "Output/Probes=" + "; ".join(items)


def slab(nx, extra=(), np=1, name=None, status=0):
    sets = ["Geometry/Blocks=slab: 0, 0, %g, %g, %d, 1" % (L, H, nx), probes(nx),
            "Output/Quantities of interest=", "Output/Figure list=", "Output/Field interval=0"]
    return run(SCENE, sets + list(extra), np=np, name=name or "steady_slab_%d" % nx,
               expect_status=status)


def errors(out, nx, profile, row=-1):
    p = read_csv(out + "/probes.csv")
    dx = L / nx
    nodal = max(abs(p["n%d_temperature" % i][row] - profile(i * dx)) for i in range(nx + 1))
    mid = [p["m%d_temperature" % i][row] - profile((i + 0.5) * dx) for i in range(nx)]
    return nodal, mid


def orders(stdout, label):
    """Residuals and contraction orders of the steady solve logged with label at t = 0."""
    m = re.search(label + r" at t = 0 s: Newton (\d+) its, \|f\| =([^m]*)mW", stdout)
    check(m is not None, "%s: Newton line printed" % label)
    if not m:
        return [], []
    r = [float(x) for x in m.group(2).split()]
    # Orders while the residual is above the round-off floor (1e-11 of the first).
    q = [math.log(r[j + 1] / r[j]) / math.log(r[j] / r[j - 1])
         for j in range(1, len(r) - 1) if r[j + 1] > 1e-11 * r[0] and r[j] != r[j - 1]]
    return r, q


# a. With the source: nodal exactness, midpoint error s dx^2 / (8 k), orders.
T_L, profile = exact_profile(T_D, s)
print("closed form: T_L = %.9f K, q_cold = %.6f mW/mm^2" % (T_L, cold_flow(T_L)))
mid_errors, balance_errors = [], []
for nx in (10, 20, 40):
    out, summary, stdout = slab(nx)
    dx = L / nx
    nodal, mid = errors(out, nx, profile)
    check(summary["status"] == "completed" and summary["steady_heat"]["solves"] == 2,
          "nx = %d: completed, steady solves at t = 0 and t = 1 s" % nx)
    check(nodal < 1e-7, "nx = %d: nodal temperatures exact to Newton's tolerance (max error %.2e K)"
          % (nx, nodal))
    predicted = -s * dx * dx / (8 * k)
    worst = max(abs(m - predicted) for m in mid)
    check(worst < 1e-7, "nx = %d: every midpoint error = -s dx^2/(8k) = %.6f K (worst deviation %.2e K)"
          % (nx, predicted, worst))
    mid_errors.append(max(abs(m) for m in mid))
    b = read_csv(out + "/steady_heat.csv")
    close(b["right_heat_in"][-1], cold_flow(T_L) * H, 1e-8, "nx = %d: cold-face heat in [mW]" % nx)
    close(b["source_heat_in"][-1], s * L * H, 1e-12, "nx = %d: source heat [mW]" % nx)
    a = (T_L - T_D + s * L * L / (2 * k)) / L
    close(b["temperature_boundaries_heat_in"][-1], -k * a * H + s * dx * H / 2, 1e-8,
          "nx = %d: hot-face heat in from k grad T . n (exact -k a H plus the secant's s dx H / 2) [mW]" % nx)
    balance_errors.append(b["balance_error"][-1])
    close(b["balance_error"][-1], s * dx / (2 * abs(cold_flow(T_L))), 1e-6,
          "nx = %d: balance error = s dx / (2 |q_cold|)" % nx)
for j in (1, 2):
    close(math.log2(mid_errors[j - 1] / mid_errors[j]), 2.0, 1e-6, "order of the max error between nodes")
    close(math.log2(balance_errors[j - 1] / balance_errors[j]), 1.0, 1e-6, "order of the balance error")

# b. No source: linear, exact everywhere.
T_L0, profile0 = exact_profile(T_D, 0.0)
out, summary, stdout = slab(20, ["Heat/Source="], name="steady_slab_nosource")
nodal, mid = errors(out, 20, profile0)
check(max(nodal, max(abs(m) for m in mid)) < 1e-7,
      "no source: nodes and midpoints exact (linear), max error %.2e K" % max(nodal, max(abs(m) for m in mid)))
close(read_csv(out + "/probes.csv")["n20_temperature"][-1], T_L0, 1e-10, "no source: T_L [K]")
check(summary["steady_heat"]["balance_error"] < 1e-9,
      "no source: balance error %.2e < 1e-9" % summary["steady_heat"]["balance_error"])

# c. Newton's convergence (from the line printed for t = 0).
stdout_source = slab(20, name="steady_slab_newton")[2]
r, q = orders(stdout_source, "steady heat")
print("  radiation + source: residuals", r, "orders", ["%.2f" % x for x in q])
check(len(r) <= 10 and q and max(q) > 1.8,
      "radiation: quadratic convergence (%d iterations, best order %.2f > 1.8)" % (len(r) - 1, max(q or [0])))
lin = slab(20, ["Heat/Source=", "Heat/Boundary conditions/Radiation="], name="steady_slab_linear")[2]
r, q = orders(lin, "steady heat")
check(len(r) == 3 and r[1] < 1e-10 * r[0],
      "linear (conduction + convection): one Newton step solves it (|f| %s mW)" % r)
b_slope, T_ref = 2e-3, 293.0


def theta(T):
    """Kirchhoff transform int_T_ref^T k0 (1 + b (u - T_ref)) du."""
    return k * ((T - T_ref) + b_slope * (T - T_ref) ** 2 / 2)


th_D = theta(T_D)
T_Lk = bisect(lambda T: (theta(T) - th_D + s * L * L / 2) / L - s * L - cold_flow(T))
kT = []
for nx in (20, 40):
    out, summary, stdout = slab(nx, ["Bodies/slab/Material/Thermal/Conductivity temperature coefficient=%g" % b_slope],
                                name="steady_slab_kT_%d" % nx)
    r, q = orders(stdout, "steady heat")
    check(q and max(q) > 1.8, "k(T), nx = %d: quadratic convergence (orders %s)" % (nx, ["%.2f" % x for x in q]))
    kT.append(abs(read_csv(out + "/probes.csv")["n%d_temperature" % nx][-1] - T_Lk))
print("  k(T): closed-form T_L = %.6f K, FE errors %s K" % (T_Lk, kT))
check(max(kT) < 1e-7, "k(T): T_L = the Kirchhoff closed form to Newton's tolerance (%.2e K)" % max(kT))

# d. Loads in time: each step the steady state of its end time.
out, summary, stdout = slab(10, ["Heat/Boundary conditions/Temperature=left: 1000 + 100*t",
                                 "Time/Time step=0.5"], name="steady_slab_ramp")
p = read_csv(out + "/probes.csv")
for row, t in enumerate(p["time"]):
    close(p["n10_temperature"][row], exact_profile(1000 + 100 * t, s)[0], 1e-9,
          "T_D = 1000 + 100 t: T_L at t = %g s [K]" % t)

# e. np = 1 vs np = 2.
o1 = slab(40, name="steady_slab_np1")[0]
o2, s2, _ = slab(40, np=2, name="steady_slab_np2")
check(s2["processes"] == 2, "second run on 2 processes")
for f in ("probes.csv", "steady_heat.csv"):
    a1, a2 = read_csv(o1 + "/" + f), read_csv(o2 + "/" + f)
    for key in a1:
        scale = max(abs(x) for x in a1[key]) or 1.0
        worst = max(abs(x - y) for x, y in zip(a1[key], a2[key]))
        # Residuals are round-off once converged: compared only to the first one's scale.
        if key.startswith("residual_last") or key.startswith("increment_last"):
            scale = max(a1["residual_first"]) if key.startswith("residual") else 1.0
        if worst > 1e-10 * scale:
            check(False, "np 1 vs 2: %s %s differs by %.2e (scale %.2e)" % (f, key, worst, scale))
            break
    else:
        check(True, "np 1 vs 2: every column of %s within 1e-10 relative" % f)

# f. A coupled scene starting from the steady field.
thermal = read_csv(o1 + "/probes.csv")
coupled_sets = ["Physics/Coupling=isothermal split", "Heat/Time integration/Method=DIRK order 3",
                "Heat/Initial temperature field=steady",
                "Bodies/slab/Material/Elasticity/Young's modulus=100000",
                "Bodies/slab/Material/Elasticity/Poisson's ratio=0.2",
                "Boundary conditions/Displacement=left: ux = 0, uy = 0",
                "Time/End time=0.1", "Time/Time step=0.1"]
out, summary, stdout = slab(40, coupled_sets, name="steady_slab_coupled")
c = read_csv(out + "/probes.csv")
worst0 = max(abs(c[key][0] - thermal[key][0]) for key in thermal if key.endswith("_temperature"))
check(worst0 < 1e-9 * T_D, "coupled, t = 0: temperatures = the thermal-only steady ones (max diff %.2e K)" % worst0)
worst1 = max(abs(c[key][-1] - c[key][0]) for key in c if key.endswith("_temperature"))
check(worst1 < 1e-3, "coupled: the steady field stays put under ARKode (max change %.2e K after 0.1 s)" % worst1)
check(len(read_csv(out + "/steady_heat.csv")["time"]) == 1, "coupled: steady_heat.csv has the t = 0 solve only")
r, q = orders(stdout, "steady initial temperature")
check(q and max(q) > 1.8, "coupled: the initial field's Newton is quadratic (orders %s)" % ["%.2f" % x for x in q])

# g. Newton that cannot converge: exit 3 with results.
out, summary, stdout = slab(20, ["Heat/Steady state/Maximum iterations=1", "Output/Field interval=1"],
                            name="steady_slab_fail", status=3)
check(summary.get("status", "").startswith("failed at t = 0 s: steady heat Newton did not converge"),
      "not converged: summary.json says so (%s)" % summary.get("status", "")[:90])
check(os.path.exists(out + "/solution.pvd") and os.path.exists(out + "/steady_heat.csv"),
      "not converged: fields and steady_heat.csv written")

finish()

"""The contact patch test (tests/contact_patch.prm): two elastic blocks stacked,
pressed by a uniform follower pressure p on the upper top, frictionless
node-to-segment penalty contact between the upper block's bottom (slave) and
the lower block's top (master). Exact answer: sigma_yy = -p, sigma_xx =
sigma_xy = 0 in both blocks, and the contact carries p times the current
width w = 1 + ux of the upper top right corner (the left sides are held in x;
the follower pressure acts on the current top, whose horizontal extent is w).

What is checked, per variant (matching 5/5 and non-matching 5/7, 7/5 cells
along the lower/upper interface; one-pass and two-pass):
 - the contact normal force sum t_N = p w to 1e-9 at every step (and, one
   pass, the vertical component of the contact force on the upper block);
 - the stress: the cell averages of sigma_yy, read by probes at every cell
   centre, per body, as max |sigma_yy + p| / p; the quantities of interest
   max(stress_yy) and min(stress_yy) (over both bodies: max/min take no body
   argument) agree with the probes; mean(stress_yy, body) = -p to 2e-4 p
   (equilibrium fixes the volume mean even where the stresses are wrong);
 - matching meshes pass the patch test to round-off, one-pass and two-pass;
 - non-matching one-pass node-to-segment does NOT pass it (the known
   defect: the slave nodes cannot transmit a uniform traction onto master
   segments they do not match): errors of 4 to 14 % of p at the cells along
   the interface, tending to a limit as the penalty grows (a consistency
   error, not a penalty error); asserted below 20 %;
 - non-matching two-pass: 8 % at c_N = 1e5 N/mm^3, below 1 % at 1e8,
   0.1 % at 1e9: it passes the test in the limit of the penalty, and is
   better than one pass from c_N = 1e7 (not at 1e5 on the 5/7 mesh);
 - mpirun -np 2 gives the same contact history to 1e-8.

The penalty study (c_N = 1e5 ... 1e9 N/mm^3) also checks that Newton converges
with the aligned ends of the two surfaces (the end slave nodes project onto
the master's end vertex): with a projection tolerance of 1e-10 on the master
parameter the end nodes flipped in and out of contact and Newton failed for
c_N <= 1e7 on non-matching meshes; the tolerance is now 1e-3.
"""
from anvil_test import run, read_csv, check, close, finish

p = 10.0
SCENE = "tests/contact_patch.prm"
NY = 3  # cells through each block's height


def cell_probes(nl, nu):
    """A probe at every cell centre: 'l<i>_<j>' in the lower block, 'u<i>_<j>' in the upper."""
    items = []
    for tag, y0, n in (("l", 0.0, nl), ("u", 0.5, nu)):
        for i in range(n):
            for j in range(NY):
                items.append("%s%d_%d: %.15g, %.15g" % (tag, i, j, (i + 0.5) / n, y0 + (j + 0.5) * 0.5 / NY))
    return "; ".join(items)


def patch(nl, nu, two_pass, cn, np=1):
    name = "contact_patch_%d_%d_%s_%g%s" % (nl, nu, "two" if two_pass else "one", cn,
                                            "_np%d" % np if np > 1 else "")
    sets = ["Geometry/Blocks=lower: 0, 0, 1, 0.5, %d, %d; upper: 0, 0.5, 1, 1, %d, %d" % (nl, NY, nu, NY),
            "Contact/interface/Two-pass=%s" % ("true" if two_pass else "false"),
            "Contact/interface/Penalty normal=%g" % cn,
            "Output/Probes=corner: 1, 1; " + cell_probes(nl, nu)]
    out, s, _ = run(SCENE, sets, np=np, name=name)
    pr, c = read_csv(out + "/probes.csv"), read_csv(out + "/contact.csv")
    q = s["quantities_of_interest"]
    r = {"summary": s, "contact": c, "q": q, "out": out}
    # Contact force history against p(t) w(t), relative to p w at the end.
    w = [1 + ux for ux in pr["corner_ux"]]
    pw = [p * t * wi for t, wi in zip(c["time"], w)]
    r["w"] = w[-1]
    r["N_err"] = max(abs(n - f) for n, f in zip(c["interface_normal"], pw)) / pw[-1]
    r["Fy_err"] = max(abs(n - f) for n, f in zip(c["interface_Fy"], pw)) / pw[-1]
    for tag in "lu":
        syy = [pr[k][-1] for k in pr if k.startswith(tag) and k.endswith("_stress_yy")]
        others = [abs(pr[k][-1]) for k in pr if k.startswith(tag) and
                  (k.endswith("_stress_xx") or k.endswith("_stress_xy"))]
        r[tag + "_max"], r[tag + "_min"] = max(syy), min(syy)
        r[tag + "_err"] = max(abs(x + p) for x in syy) / p
        r[tag + "_other"] = max(others) / p
    r["err"] = max(r["l_err"], r["u_err"])
    return r


def label(nl, nu, two_pass):
    return "%d/%d %s" % (nl, nu, "two-pass" if two_pass else "one-pass")


print("p = %g MPa; errors relative to p; stresses: cell averages at the cell centres, at t = 1" % p)
print("  %-15s %9s %10s %10s %10s %10s %10s %10s %10s %10s %10s %6s" % (
    "lower/upper", "c_N", "sum t_N", "N-pw rel", "lower max", "lower min", "upper max", "upper min",
    "err lower", "err upper", "sxx,sxy", "active"))


def show(nl, nu, two_pass, cn, r):
    print("  %-15s %9.0e %10.6f %10.2e %10.5f %10.5f %10.5f %10.5f %10.2e %10.2e %10.2e %6d" % (
        label(nl, nu, two_pass), cn, r["contact"]["interface_normal"][-1], r["N_err"],
        r["l_max"], r["l_min"], r["u_max"], r["u_min"], r["l_err"], r["u_err"],
        max(r["l_other"], r["u_other"]), r["contact"]["interface_active_nodes"][-1]))


CN = 1e8
results = {}
for nl, nu in ((5, 5), (5, 7), (7, 5)):
    for two_pass in (False, True):
        r = patch(nl, nu, two_pass, CN)
        results[(nl, nu, two_pass)] = r
        show(nl, nu, two_pass, CN, r)

for (nl, nu, two_pass), r in results.items():
    what = label(nl, nu, two_pass)
    q = r["q"]
    check(r["summary"]["status"] == "completed" and r["contact"]["time"][-1] == 1.0,
          "%s: ran to t = 1" % what)
    # sum t_N = p w to 1e-9: the residual's round-off floor is ~ c_N h eps ~ 2e-9 N
    # against p w = 10 N; the tilt of the non-matching interface (n_y = cos theta,
    # theta ~ 4e-5) adds sum t_N theta^2 / 2 ~ 1e-9 N, measured <= 8.4e-10 relative.
    check(r["N_err"] <= 1e-9, "%s: contact normal force sum t_N = p w at every step (max error %.2e p w)"
          % (what, r["N_err"]))
    if not two_pass:
        check(r["Fy_err"] <= 1e-9, "%s: vertical contact force on the upper block = p w at every step "
              "(max error %.2e p w)" % (what, r["Fy_err"]))
    # The quantities of interest max/min(stress_yy) are over both bodies and
    # over the quadrature points (issue 16): the cell probes (cell averages,
    # 12 significant digits in probes.csv) lie inside their range, and where
    # the patch is passed exactly (uniform stress) they are equal.
    hi, lo = max(r["l_max"], r["u_max"]), min(r["l_min"], r["u_min"])
    if r["err"] < 1e-9:
        close(q["syy_max"], hi, 1e-10, "%s: max(stress_yy) over the points = max of the cell probes (uniform)" % what)
        close(q["syy_min"], lo, 1e-10, "%s: min(stress_yy) over the points = min of the cell probes (uniform)" % what)
    else:
        check(q["syy_max"] >= hi - 1e-10 * p and q["syy_min"] <= lo + 1e-10 * p,
              "%s: max/min(stress_yy) over the points %.6g / %.6g enclose the cell probes' %.6g / %.6g"
              % (what, q["syy_max"], q["syy_min"], hi, lo))
    # The volume means follow from equilibrium (virtual work with a linear test
    # field) up to the strain level (reference volume weights, ~ 1e-4) even
    # where the pointwise stresses are wrong.
    for b in ("lower", "upper"):
        close(q["syy_" + b], -p, 2e-4, "%s: mean(stress_yy, %s) = -p up to the strain (p/E = 1.4e-4)" % (what, b))

# Not asserted: with Two-pass the force columns of contact.csv add the second
# pass's force, which acts on the lower block, to the first's on the upper.
print("  two-pass contact(interface, y) at t = 1 (not a force on one body): %s"
      % ", ".join("%d/%d %.6f" % (nl, nu, results[(nl, nu, True)]["q"]["Fy"]) for nl, nu in ((5, 5), (5, 7), (7, 5))))

# Matching meshes: the nodes coincide, the patch test passes to round-off
# (measured ~ 1e-12 p, bound 1e-9 p).
for two_pass in (False, True):
    r = results[(5, 5, two_pass)]
    check(r["err"] <= 1e-9 and max(r["l_other"], r["u_other"]) <= 1e-9,
          "%s: uniform sigma_yy = -p and sigma_xx = sigma_xy = 0 in both blocks (error %.2e p)"
          % (label(5, 5, two_pass), max(r["err"], r["l_other"], r["u_other"])))
# Non-matching one pass: the known failure, bounded (measured 3.9 % to 13.5 %).
for nl, nu in ((5, 7), (7, 5)):
    one, two = results[(nl, nu, False)], results[(nl, nu, True)]
    check(one["err"] < 0.2, "%s: patch test error %.2f %% of p (node-to-segment one pass does not pass "
          "it; bound 20 %%)" % (label(nl, nu, False), 100 * one["err"]))
    check(two["err"] < 0.01, "%s: patch test error %.3f %% of p (bound 1 %% at c_N = %g)"
          % (label(nl, nu, True), 100 * two["err"], CN))
    check(two["err"] < one["err"] / 5, "%d/%d: two-pass (%.2e) is better than one-pass (%.2e) by %.0fx"
          % (nl, nu, two["err"], one["err"], one["err"] / two["err"]))

# Penalty study on the non-matching meshes, c_N = 1e5 ... 1e9 N/mm^3 (E/h of
# the interface cells is 4e5 to 5e5 N/mm^3). Above ~1e9 the residual's
# round-off floor (~ c_N h eps) exceeds Newton's tolerance (1e10 fails).
print("  penalty study (the force tolerances grow with c_N above 1e8: the residual's round-off floor is ~ c_N h eps)")
PENALTIES = (1e5, 1e6, 1e7, 1e8, 1e9)
errors = {}
for nl, nu in ((5, 7), (7, 5)):
    for two_pass in (False, True):
        what = label(nl, nu, two_pass)
        errs = []
        for cn in PENALTIES:
            r = results[(nl, nu, two_pass)] if cn == CN else patch(nl, nu, two_pass, cn)
            if cn != CN:
                show(nl, nu, two_pass, cn, r)
            tol = 1e-9 * max(1, cn / 1e8)
            if two_pass:
                check(r["N_err"] <= tol, "%s, c_N = %g: sum t_N = p w (error %.2e p w)" % (what, cn, r["N_err"]))
            else:
                # One pass: the vertical force is p w exactly (equilibrium of the
                # upper block); sum t_N exceeds it by sum t_N (1 - n_y), the tilt
                # of the master segments (measured <= 1.6e-9 p w, at c_N = 1e5).
                check(r["Fy_err"] <= tol and r["N_err"] <= 5 * tol,
                      "%s, c_N = %g: vertical contact force = p w (error %.2e p w), sum t_N = p w "
                      "(error %.2e p w)" % (what, cn, r["Fy_err"], r["N_err"]))
            errs.append(r["err"])
        errors[(nl, nu, two_pass)] = errs
        listing = ", ".join("%.2e" % e for e in errs)
        if two_pass:
            # measured: 7.9e-2 .. 1.1e-3 (5/7), 7.7e-2 .. 1.2e-3 (7/5), monotone
            check(all(a > b for a, b in zip(errs, errs[1:])) and errs[0] / errs[-1] > 20,
                  "%s: the error falls as the penalty grows: %s (1e5 -> 1e9: / %.0f)"
                  % (what, listing, errs[0] / errs[-1]))
        else:
            # measured: 5.0 % to 5.1 % (5/7), 13.4 % to 13.5 % (7/5) from 1e7 to 1e9
            check(max(errs) < 0.2 and (errs[-1] < 1e-6 or abs(errs[-1] / errs[2] - 1) < 0.05),
                  "%s: the error tends to a limit (%.1f %% of p) instead of 0: %s (a consistency "
                  "error of one-pass node-to-segment, not a penalty error)"
                  % (what, 100 * errs[-1], listing))
    one, two = errors[(nl, nu, False)], errors[(nl, nu, True)]
    print("  %d/%d: two-pass error / one-pass error per c_N: %s" % (
        nl, nu, ", ".join("%g: %.2f" % (cn, b / a) for cn, a, b in zip(PENALTIES, one, two))))
    # Two passes are better from c_N = 1e7 (at 1e5 the 5/7 one-pass is better).
    check(all(b < a for a, b in list(zip(one, two))[2:]),
          "%d/%d: two-pass is better than one-pass for c_N >= 1e7" % (nl, nu))

# np = 1 and np = 2: the same contact history.
for two_pass in (False, True):
    a = results[(5, 7, two_pass)]["contact"]
    b = patch(5, 7, two_pass, CN, np=2)
    worst = max(abs(x - y) for key in a for x, y in zip(a[key], b["contact"][key]))
    check(b["summary"]["processes"] == 2 and len(a["time"]) == len(b["contact"]["time"]) and worst < 1e-8,
          "%s: np = 1 vs np = 2: contact history differs by %.2e (max over all columns and steps)"
          % (label(5, 7, two_pass), worst))
finish()

"""A block pressed and slid on a rigid plane (tests/contact_block.prm): node-to-
tool penalty contact with Coulomb friction (seed eq. 27-29).

 - Pressing (10 MPa on a 1 mm wide top): the contact carries N = p w = 10 N/mm.
 - While it sticks, every bottom node's tangential force is its elastic slip
   times c_T (eq. 28): sum |t_T| = c_T sum |u_x| over the bottom nodes.
 - Sliding: the tangential force is mu N (eq. 29) and the friction work grows
   by mu N times the slide of each step.
 - Stick -> slip: with a soft c_T the force climbs over several steps, never
   above mu N, and the whole block slides once it reaches mu N; with
   mu_s = 0.3 > mu_d = 0.2 it slides at mu_d N (the element test checks the
   mu_s peak node by node).
 - Penalty study: the penetration is N_node / c_N and tends to 0 as c_N grows,
   while the contact force stays p w; Newton iterations are printed.
 - np = 1 and np = 2 give the same contact forces.
"""
from anvil_test import run, read_csv, check, close, finish

p, w, mu, c_T = 10.0, 1.0, 0.3, 1e4
out, s, _ = run("tests/contact_block.prm", name="contact_friction")
c = read_csv(out + "/contact.csv")
pr = read_csv(out + "/probes.csv")
k = c["time"].index(1.0)
close(c["sliding_normal"][k], p * w, 1e-9, "pressed: contact normal force = p w (N/mm)")
close(c["sliding_Fy"][k], p * w, 1e-9, "pressed: force on the block from the floor, y (N/mm)")
ux = sum(abs(pr["n%d_ux" % i][k]) for i in range(5))
close(c["sliding_tangential"][k], c_T * ux, 1e-9,
      "sticking: sum |t_T| = c_T sum |u_x| of the bottom nodes (elastic slip, eq. 28)")
check(c["sliding_sliding_nodes"][k] == 0, "nothing slides while pressing")
last = len(c["time"]) - 1
close(c["sliding_tangential"][last], mu * p * w, 1e-9, "sliding: tangential force = mu N (eq. 29)")
close(-c["sliding_Fx"][last], mu * p * w, 1e-9, "sliding: the floor pulls the block back by mu N")
check(c["sliding_sliding_nodes"][last] == c["sliding_active_nodes"][last] > 0,
      "sliding: every node in contact slides (%d)" % c["sliding_active_nodes"][last])
dW = c["sliding_friction_work"][last] - c["sliding_friction_work"][last - 1]
close(dW, mu * p * w * 0.005, 1e-6, "friction work of a sliding step = mu N x slide (N mm/mm)")
print("  top reaction Fx at the end %.6f N/mm (mu N = 3; the follower pressure on the tilted top adds %.1e)"
      % (s["quantities_of_interest"]["Fx"], s["quantities_of_interest"]["Fx"] - 3))

# The stick -> slip transition: with a soft tangential penalty (c_T = 100
# N/mm) the sticking phase spans several steps; the tangential force climbs,
# never above mu N, and the block slides as a whole once it reaches mu N.
out, s, _ = run("tests/contact_block.prm", ["Contact/sliding/Penalty tangent=100", "Time/Time step=0.02"],
                name="contact_friction_transition")
c = read_csv(out + "/contact.csv")
T, slide, active = c["sliding_tangential"], c["sliding_sliding_nodes"], c["sliding_active_nodes"]
phase2 = [i for i, t in enumerate(c["time"]) if t > 1]
full = next(i for i in phase2 if slide[i] == active[i] > 0)
first = next(i for i in phase2 if slide[i] > 0)
print("  c_T = 100: T = %s ... N/mm; first node slips at t = %.2f s, all slide from t = %.2f s (T = %.6f)"
      % (" ".join("%.3f" % T[i] for i in phase2[:8]), c["time"][first], c["time"][full], T[full]))
check(all(T[i] <= mu * p * w * (1 + 1e-9) for i in phase2), "the tangential force never exceeds mu N")
check(all(T[i] < T[i + 1] for i in phase2[:full - phase2[0]]), "it grows while the block sticks")
check(full - phase2[0] >= 3, "sticking lasts several steps (%d)" % (full - phase2[0]))
close(T[full], mu * p * w, 1e-9, "the block slides as a whole when T reaches mu N")

# Static above dynamic: sliding continues at mu_d N.
out, s, _ = run("tests/contact_block.prm", ["Contact/sliding/Dynamic friction coefficient=0.2"],
                name="contact_friction_dynamic")
c = read_csv(out + "/contact.csv")
close(c["sliding_tangential"][-1], 0.2 * p * w, 1e-9, "mu_s = 0.3, mu_d = 0.2: sliding at mu_d N = 2")

# Penalty study: gap -> 0 as c_N grows, the force stays p w.
print("  %10s %14s %14s %10s %8s" % ("c_N N/mm", "penetration mm", "N/node expected", "force", "Newton"))
prev = None
tops = []
for cn in (1e3, 1e4, 1e5, 1e6, 1e7):
    out, s, _ = run("tests/contact_block.prm", ["Contact/sliding/Penalty normal=%g" % cn, "Time/End time=1",
                                                "Output/Probes=top: 0.5, 1",
                                                "Output/Quantities of interest=uy: probe(top, uy)"],
                    name="contact_friction_penalty_%g" % cn)
    tops.append(s["quantities_of_interest"]["uy"])
    c = read_csv(out + "/contact.csv")
    pen = c["sliding_max_penetration"][-1]
    newton = s["newton_iterations"] / s["steps"]
    print("  %10.0e %14.4e %14.4e %10.6f %8.2f" % (cn, pen, p * w / 4 / cn, c["sliding_normal"][-1], newton))
    close(c["sliding_normal"][-1], p * w, 1e-9, "c_N = %g: the contact carries p w" % cn)
    # An interior node carries about p w / 4 (tributary 0.25 mm): penetration ~ N_node / c_N.
    check(0.5 * p * w / 4 / cn < pen < 2 * p * w / 4 / cn, "c_N = %g: penetration %.3e ~ N_node/c_N" % (cn, pen))
    if prev:
        # (the nodal forces redistribute with the stiffness ratio: -> 10 as c_N grows)
        close(prev / pen, 10, 0.12, "penetration shrinks with 1/c_N")
    check(newton <= 3, "c_N = %g: %.2f Newton iterations per step" % (cn, newton))
    prev = pen

# The answer converges as c_N grows: the top's settlement differs from the
# stiffest run by ~ N_node/c_N.
diffs = [abs(u - tops[-1]) for u in tops[:-1]]
print("  top settlement uy: %s mm; differences to c_N = 1e7: %s" % (" ".join("%.8f" % u for u in tops),
                                                                  " ".join("%.2e" % x for x in diffs)))
check(all(diffs[i + 1] < 0.2 * diffs[i] for i in range(len(diffs) - 1)),
      "the settlement converges as c_N grows (differences shrink ~10x per decade)")

# A moving tool: a rigid plane (Motion = 0, -d t) presses the block down onto
# rollers, frictionless, penalty per area c_N: p = E' (d - p/c_N)/H, i.e.
# p = E' d / (H + E'/c_N) with E' = E/(1 - nu^2) (plane strain, free sides).
E, nu, H, d, cN = 70000.0, 0.3, 1.0, 1e-3, 1e6
Ep = E / (1 - nu * nu)
out, s, _ = run("tests/contact_block.prm",
                ["Contact/Tools=floor, press", "Contact/sliding/Slave=top", "Contact/sliding/Master=press",
                 "Contact/sliding/Penalty per=area", "Contact/sliding/Penalty normal=%g" % cN,
                 "Contact/sliding/Penalty tangent=0", "Contact/sliding/Friction coefficient=0",
                 "Contact/press/Type=plane", "Contact/press/Point=0, 1", "Contact/press/Normal=0, -1",
                 "Contact/press/Motion=0, -%g*t" % d,
                 "Boundary conditions/Displacement=bottom: uy = 0; left: ux = 0",
                 "Boundary conditions/Pressure=", "Time/End time=1", "Output/Probes=",
                 "Output/Quantities of interest=N: contact(sliding, normal); R: reaction(bottom, y)"],
                name="contact_friction_press")
q = s["quantities_of_interest"]
expected = Ep * d / (H + Ep / cN) * 1.0
print("  moving plane: contact force %.6f N/mm, bottom reaction %.6f, closed form %.6f" % (q["N"], q["R"], expected))
close(q["N"], expected, 2e-3, "moving tool: p w = E' d/(H + E'/c_N) (small strain, O(d/H) finite-strain terms)")
close(q["R"], q["N"], 1e-9, "the supports carry the tool's force")

# Heat with a tool (eq. 30-34): (a) steady conduction from the floor at
# 400 K through the contact conductance into the block, whose top is held at
# 300 K: q = (400 - 300)/(1/h + L/k), h = h0 (p/H)^e; (b) an insulated block
# sliding on the floor keeps the relative-effusivity share of the friction
# work, the rest goes to the tool.
heat = ["Physics/Coupling=isothermal split", "Heat/Initial temperature=300",
        "Bodies/block/Material/Thermal/Conductivity=150",
        "Contact/sliding/Thermal/Conductance=150", "Contact/sliding/Thermal/Hardness=932",
        "Contact/sliding/Thermal/Exponent=0.95", "Contact/floor/Temperature=400", "Output/Probes=",
        "Output/Quantities of interest=Tb: mean(temperature)"]
# (frictionless, left side on rollers, penalty per area: the pressure, hence h,
# is uniform; a per-node penalty stiffens the corners, which then carry more)
out, s, _ = run("tests/contact_block.prm", heat + ["Heat/Boundary conditions/Temperature=top: 300",
                                                   "Boundary conditions/Displacement=left: ux = 0",
                                                   "Contact/sliding/Friction coefficient=0",
                                                   "Contact/sliding/Penalty tangent=0",
                                                   "Contact/sliding/Penalty per=area",
                                                   "Contact/sliding/Penalty normal=1e7",
                                                   "Time/End time=20", "Time/Maximum time step=2",
                                                   "Output/Probes=b: 0.5, 0",
                                                   "Output/Quantities of interest=Tb: probe(b, temperature)"],
                name="contact_friction_tool_conduction")
h = 150 * (10 / 932.0) ** 0.95
qf = 100 / (1 / h + 1.0 / 150)
print("  hot floor: block bottom %.5f K, series resistance %.5f K" % (s["quantities_of_interest"]["Tb"], 400 - qf / h))
close(s["quantities_of_interest"]["Tb"], 400 - qf / h, 0, "steady conduction from a tool (K)", atol=1e-3)
out, s, _ = run("tests/contact_block.prm", heat + ["Contact/floor/Temperature=300",
                                                   "Contact/sliding/Thermal/Conductance=0",
                                                   "Contact/sliding/Thermal/Relative effusivity=0.3"],
                name="contact_friction_tool_heat")
Wf = s["contact"]["sliding_friction_work"]
print("  sliding on the floor: heat into the block %.6f mJ, friction work %.6f" % (s["heat"]["heat_content_change"], Wf))
close(s["heat"]["heat_content_change"], 0.3 * Wf, 1e-8, "the block keeps 0.3 of the friction heat (insulated)")
check(s["heat"]["balance_error"] < 1e-9, "heat balance closes (%.1e)" % s["heat"]["balance_error"])

# Excessive penetration: a limit below what the penalty allows cuts the step
# back, then stops the run (status 3) saying why.
out, s, _ = run("tests/contact_block.prm", ["Contact/Maximum penetration=1e-6", "Time/Minimum time step=0.025"],
                name="contact_friction_penetration", expect_status=3)
check("penetration" in s["status"] and s["cut_backs"] > 0,
      "excessive penetration is reported and cut back: " + s["status"])

# np = 1 and np = 2: the same contact forces.
o1, _, _ = run("tests/contact_block.prm", ["Geometry/Blocks=block: 0, 0, 1, 1, 8, 8"], name="contact_friction_np1")
o2, s2, _ = run("tests/contact_block.prm", ["Geometry/Blocks=block: 0, 0, 1, 1, 8, 8"], np=2, name="contact_friction_np2")
a, b = read_csv(o1 + "/contact.csv"), read_csv(o2 + "/contact.csv")
worst = max(abs(x - y) for key in a for x, y in zip(a[key], b[key]))
check(s2["processes"] == 2 and worst < 1e-8, "np = 1 vs np = 2: contact history differs by %.2e" % worst)
finish()

"""Thermomechanical contact: the seed's two-block scene (prm/two_blocks.prm, with
the reconstruction of the lost figure in its header) and the checks of contact heat (seed eq. 30-34).

1. Two blocks: friction work W = mu p w s = 9.375 N mm/mm, half into each block;
   with the contact exchange stopped each insulated block becomes uniform at
   its mean temperature (its heat content over rho c V): delta_T_upper =
   4.6875/(2.43 x 1.5625) = 1.2346 K, delta_T_lower = 4.6875/(2.43 x 6.25) =
   0.3086 K, asserted to 0.5 %. The seed's Table 4 is printed beside ours.
2. Frictional heat split (no conductance, insulated): the slave block's heat
   is the relative effusivity times the friction work, the master's the rest,
   and all of it equals the friction work (eq. 31-33).
3. Steady conduction through two blocks pressed together (tests/contact_conduction.prm):
   interface temperatures against the series resistance L/k + 1/h + L/k with
   h = h0 (p/H)^e (eq. 34), matching and non-matching meshes, 2D and 3D.
4. With Table 1's thermal expansion the thermoelastic heat is reported beside
   the contact heat, and the heat balance closes.
5. np = 1 and np = 2: the same contact forces and temperatures.
6. A checkpoint in the middle of the slide, resumed on two processes, ends
   with the uninterrupted run's answer.
"""
from anvil_test import run, read_csv, check, close, finish

rho_c, mu, p, w, s_slide = 2.7e-9 * 0.9e9, 0.2, 10.0, 1.25, 3.75
W = mu * p * w * s_slide
V_upper, V_lower = 1.25 * 1.25, 5 * 1.25
out, s, _ = run("prm/two_blocks.prm", ["Output/Field interval=0"], name="two_blocks")
q, heat, c = s["quantities_of_interest"], s["heat"], s["contact"]
print("  %-34s %10s %10s" % ("", "seed", "anvil"))
print("  %-34s %10s %10.4f" % ("delta T upper (analytic 1.2346 K)", "1.231", q["delta_T_upper"]))
print("  %-34s %10s %10.4f" % ("delta T lower (analytic 0.3086 K)", "0.307", q["delta_T_lower"]))
print("  %-34s %10d %10d" % ("time steps", 77, s["steps"]))
print("  %-34s %10d %10d" % ("Newton iterations", 217, s["newton_iterations"]))
print("  %-34s %10.2f %10.2f" % ("CPU s (seed: 2002 hardware)", 18.33, s["wall_time"]))
print("  friction work %.5f N mm/mm (mu p w s = %.5f), heat exchanged upper -> lower %.5f mJ, "
      "ARKode steps per step %.2f" % (c["interface_friction_work"], W, c["interface_heat_exchanged"],
                                      heat["arkode_steps_per_step"]))
close(q["delta_T_upper"], W / 2 / (rho_c * V_upper), 5e-3, "delta_T_upper (K)")
close(q["delta_T_lower"], W / 2 / (rho_c * V_lower), 5e-3, "delta_T_lower (K)")
close(c["interface_friction_work"], W, 5e-3, "friction work = mu p w s (the first steps stick elastically)")
close(heat["contact_heat"], c["interface_friction_work"], 1e-9, "all the friction work becomes heat in the blocks")
close(heat["heat_content_change"], heat["contact_heat"] + heat["thermoelastic_heat"], 1e-9,
      "heat balance: content change = contact heat + thermoelastic heat")

# Newton with the exact contact tangents: the order of the last contraction
# above the round-off floor, in every step that has one (quadratic: ~2).
import math
nc = read_csv(out + "/newton.csv")
steps = {}
for st, r, conv in zip(nc["step"], nc["residual"], nc["converged"]):
    if conv:
        steps.setdefault(st, []).append(r)
orders = []
floor = 1e-8  # N: below, the residual is round-off (the scene's tolerance is ~1e-10 relative)
for r in steps.values():
    triples = [(r[k - 1], r[k], r[k + 1]) for k in range(1, len(r) - 1)
               if r[k + 1] > floor and r[k - 1] > r[k] > r[k + 1] and r[k] < 0.1 * r[k - 1]]
    if triples:
        a, b, c_ = triples[-1]
        orders.append(math.log(c_ / b) / math.log(b / a))
orders.sort()
median = orders[len(orders) // 2]
print("  Newton: %d steps measured, median order of the last contraction %.2f" % (len(orders), median))
check(median > 1.5, "Newton converges quadratically with contact and friction (median order %.2f)" % median)

# The assembled tangent with the contact elements against central finite
# differences of the assembled residual (Mechanics/Newton/Check tangent),
# over the pressing and the start of the slide. The first check sits on the
# kink where the nodes touch (g = 0), where the residual has no derivative.
import re
_, _, stdout = run("prm/two_blocks.prm", ["Output/Field interval=0", "Time/End time=5e-4",
                                          "Mechanics/Newton/Check tangent=true"], name="two_blocks_tangent")
errors = [float(m.group(1)) for m in re.finditer(r"tangent check: \|K du - FD\| / \|K du\| = (\S+)", stdout)]
print("  tangent vs FD with contact: %d checks, first %.1e (contact onset), then at most %.1e"
      % (len(errors), errors[0], max(errors[1:])))
check(len(errors) > 5 and max(errors[1:]) < 1e-7, "the contact tangent is exact (%.1e)" % max(errors[1:]))

# 2. The split of the frictional heat (no conduction across the interface).
share = 0.3
out, s, _ = run("prm/two_blocks.prm", ["Output/Field interval=0", "Contact/interface/Thermal/Conductance=0",
                                       "Contact/interface/Thermal/Relative effusivity=%g" % share],
                name="two_blocks_split")
q = s["quantities_of_interest"]
Wf = s["contact"]["interface_friction_work"]
H_upper, H_lower = q["delta_T_upper"] * rho_c * V_upper, q["delta_T_lower"] * rho_c * V_lower
print("  split 0.3: upper %.6f mJ, lower %.6f mJ, friction work %.6f N mm" % (H_upper, H_lower, Wf))
close(H_upper, share * Wf, 1e-8, "slave (upper) heat = relative effusivity x friction work")
close(H_lower, (1 - share) * Wf, 1e-8, "master (lower) heat = the rest")
close(H_upper + H_lower, Wf, 1e-9, "total heat = friction work (insulated blocks)")

# 3. Steady conduction through pressed blocks.
h = 150 * (10 / 932.0) ** 0.95
qflux = (400 - 300) / (1 / 150.0 + 1 / h + 1 / 150.0)
T_l, T_u = 400 - qflux / 150, 300 + qflux / 150
for name, blocks, tol in (("matching", "lower: 0, 0, 1, 1, 4, 4; upper: 0, 1, 1, 2, 4, 4", 1e-3),
                          ("non-matching", "lower: 0, 0, 1, 1, 4, 4; upper: 0, 1, 1, 2, 6, 4", 0.05)):
    out, s, _ = run("tests/contact_conduction.prm", ["Geometry/Blocks=" + blocks], name="contact_conduction_" + name)
    q = s["quantities_of_interest"]
    print("  steady conduction, %s meshes: h = %.5f mW/(mm^2 K), interface %.5f / %.5f K (series resistance: "
          "%.5f / %.5f K)" % (name, h, q["T_lower"], q["T_upper"], T_l, T_u))
    close(q["T_lower"], T_l, 0, "%s: lower interface temperature (K)" % name, atol=tol)
    close(q["T_upper"], T_u, 0, "%s: upper interface temperature (K)" % name, atol=tol)

# The same in 3D (node-to-facet, non-matching 3 x 3 / 4 x 4 facets).
out, s, _ = run("tests/contact_conduction.prm",
                ["Dimension=3", "Geometry/Blocks=lower: 0, 0, 0, 1, 1, 1, 3, 3, 3; upper: 0, 1, 0, 1, 2, 1, 4, 3, 4",
                 "Boundary conditions/Displacement=lower.bottom: uy = 0; lower.left: ux = 0; upper.left: ux = 0; "
                 "lower.front: uz = 0; upper.front: uz = 0",
                 "Output/Probes=lower_surface: 0.5, 0.9999999, 0.5; upper_surface: 0.5, 1.0000001, 0.5"],
                name="contact_conduction_3d")
q = s["quantities_of_interest"]
print("  steady conduction, 3D non-matching facets: interface %.5f / %.5f K" % (q["T_lower"], q["T_upper"]))
close(q["T_lower"], T_l, 0, "3D: lower interface temperature (K)", atol=0.05)
close(q["T_upper"], T_u, 0, "3D: upper interface temperature (K)", atol=0.05)

# 4. Table 1's thermal expansion: the thermoelastic heat, reported separately.
beta = ["Bodies/%s/Material/Elasticity/Thermal expansion=23.86e-6" % b for b in ("upper", "lower")]
out, s, _ = run("prm/two_blocks.prm", ["Output/Field interval=0"] + beta, name="two_blocks_beta")
heat, q = s["heat"], s["quantities_of_interest"]
print("  with beta = 23.86e-6: contact heat %.5f mJ, thermoelastic heat %.5f mJ (%.2f %%), delta T %.4f / %.4f K"
      % (heat["contact_heat"], heat["thermoelastic_heat"], 100 * heat["thermoelastic_heat"] / heat["contact_heat"],
         q["delta_T_upper"], q["delta_T_lower"]))
check(heat["balance_error"] < 1e-10, "heat balance closes with the thermoelastic heat (%.1e)" % heat["balance_error"])
check(0 < heat["thermoelastic_heat"] < 0.02 * heat["contact_heat"],
      "the thermoelastic heat is small beside the friction heat")

# 5. One and two processes.
sets = ["Output/Field interval=0", "Time/End time=1e-3", "Output/Probes=p: 0.6, 1.25"]
o1, s1, _ = run("prm/two_blocks.prm", sets, name="two_blocks_np1")
o2, s2, _ = run("prm/two_blocks.prm", sets, np=2, name="two_blocks_np2")
a, b = read_csv(o1 + "/contact.csv"), read_csv(o2 + "/contact.csv")
worst = max(abs(x - y) / max(1.0, abs(x)) for k in a for x, y in zip(a[k], b[k]))
check(s2["processes"] == 2 and worst < 1e-8, "np = 1 vs 2: contact history differs by %.1e" % worst)
ta, tb = read_csv(o1 + "/probes.csv")["p_temperature"], read_csv(o2 + "/probes.csv")["p_temperature"]
dT = max(abs(x - y) for x, y in zip(ta, tb))
check(dT < 1e-10 * max(ta), "np = 1 vs 2: the same interface temperature history to 1e-10 relative "
      "(solver tolerance; issue 17): largest difference %.1e K" % dT)

# 6. Checkpoint: stopped at t = 2 ms (sliding) and resumed on two processes,
#    the contact history (stick/slip states, tangential forces, friction
#    work) comes back: the same answer as the uninterrupted run.
import os
out_half, _, _ = run("prm/two_blocks.prm", ["Output/Field interval=0", "Time/End time=2e-3"], name="two_blocks_half")
_, resumed, _ = run("prm/two_blocks.prm", ["Output/Field interval=0", "Output/Restart from=" + out_half + "/checkpoint"],
                    np=2, name="two_blocks_half")
full = run("prm/two_blocks.prm", ["Output/Field interval=0"], name="two_blocks")[1]
for k in ("delta_T_upper", "delta_T_lower", "friction_work"):
    close(resumed["quantities_of_interest"][k], full["quantities_of_interest"][k], 1e-9, "resumed on 2 processes: " + k)
check(os.path.exists(out_half + "/contact.pvd"), "contact fields written (contact.pvd)")
finish()

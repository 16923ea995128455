"""The scene of doc/user_guide.md (doc/first_scene.prm) runs and gives the
upsetting loads of the closed forms.

1. Frictionless (--set friction 0): the billet stays a cylinder, the axial
   stress is the flow stress sigma = sigma_0 + h eps_p with eps_p =
   ln(h0/h) - sigma/E (h from the top's displacement), checked at the corner
   probe to 0.5 %; the radius follows volume conservation, r = r0 sqrt(h0/h);
   the die force is sigma pi r^2 to 2 %: with the penalty per node (the
   guide's choice) each face node gets the same stiffness whatever its ring
   area, so the die face is not pressed quite uniformly (measured -1.3 %).
2. With the guide's friction 0.1 the force rises by the slab method's factor
   1 + 2 mu r / (3 h) (Schey, Tribology in Metalworking; r, h the current
   radius and full height), to 2 %: barrelling and sticking near the axis
   make the slab estimate approximate.
"""
import math

from anvil_test import run, read_csv, check, close, finish

E, s0, H, r0, h0 = 200000.0, 250.0, 800.0, 5.0, 5.0   # h0: the modelled half height
out, s, stdout = run("doc/first_scene.prm", ["Contact/die_contact/Friction coefficient=0",
                                             "Output/Figures=false"], name="user_guide_mu0")
p = read_csv(out + "/probes.csv")
h = h0 + p["corner_uy"][-1]                      # the top face's height now
F = -s["quantities_of_interest"]["die_force"]
# Solve F = (s0 + H eps_p) A with eps_p = ln(h0/h) - F/(A E) (uniaxial, log strains).
area = math.pi * r0 ** 2 * h0 / h
sigma = s0
for _ in range(50):
    sigma = s0 + H * (math.log(h0 / h) - sigma / E)
print("  frictionless: h = %.4f mm, anvil F = %.1f N, closed form %.1f N" % (h, F, sigma * area))
close(-p["corner_stress_yy"][-1], sigma, 5e-3, "frictionless upsetting: axial stress = sigma_y(eps_p) (MPa)")
close(F, sigma * area, 2e-2, "frictionless upsetting: F = sigma_y(eps_p) A (N)")
close(p["corner_ux"][-1], r0 * (math.sqrt(h0 / h) - 1), 5e-3, "no barrelling: r = r0 sqrt(h0/h) (mm)")

out, s, stdout = run("doc/first_scene.prm", ["Output/Figures=false"], name="user_guide")
F_mu = -s["quantities_of_interest"]["die_force"]
p = read_csv(out + "/probes.csv")
h = h0 + p["corner_uy"][-1]
r = r0 * math.sqrt(h0 / h)
slab = 1 + 2 * 0.1 * r / (3 * 2 * h)
print("  friction 0.1: F = %.1f N, ratio to frictionless %.4f, slab method %.4f" % (F_mu, F_mu / F, slab))
close(F_mu / F, slab, 2e-2, "friction raises the force by 1 + 2 mu r / (3 h)")
check(s["quantities_of_interest"]["T_max"] > 293, "plastic and frictional heating warm the billet")
finish()

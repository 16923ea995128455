"""Axisymmetric contact with Penalty per = area: the node on the axis.

A disk of radius 1 mm pressed by p = 10 MPa onto a rigid frictionless plane
(tests/contact_block.prm, axisymmetric, c_N = 1e5 N/mm^3 per unit area).
Each bottom node's area is its share of the rings its segments sweep,
the integral of its shape function (2 pi r = 0 gave the axis node no force);
the shares are those of a uniform pressure's nodal forces and add up to
pi R^2, so:
1. the total contact force is p pi R^2 (statics);
Before, the axis node had no area: it sank 1.5e-4 mm (50 % more) and
contact.csv reported 1.026e-4 mm, not its penetration.
2. the penetration is p / c_N = 1e-4 mm under every node, the axis node
   included, to 1e-4 (the follower pressure on the widened top; with the
   disk of half the segment, pi L^2/4, as the axis node's area it was 9 %
   deeper);
3. contact.csv's maximum penetration is the largest of the nodes'.
4. The axis node also conducts (eq. 34): the disc at 300 K on the tool at
   400 K exchanges h A (T0 - T_tool) over a step of 1 us with
   h = h0 (p/H)^e and A = pi R^2. The conductance's area is the same ring
   share as the penalty's, so the pressure t_N / A is p at every node; with
   2 pi r_node L/2 the axis node had no area and conducted nothing and the
   rim node's pressure was low by L/3R: 2.4 % less heat.
"""
import math

from anvil_test import run, read_csv, check, close, finish

p, c, R = 10.0, 1e5, 1.0
out, s, _ = run("tests/contact_block.prm", [
    "Mechanics/Two-dimensional model=axisymmetric", "Time/End time=1",
    "Boundary conditions/Displacement=", "Contact/sliding/Friction coefficient=0",
    "Contact/sliding/Penalty per=area", "Contact/sliding/Penalty normal=%g" % c,
    "Contact/sliding/Penalty tangent=%g" % c], name="contact_axis")
q = s["quantities_of_interest"]
# The pressure follows the top face, which widens by ~nu p / E: 1e-4 relative.
close(q["N"], p * math.pi * R ** 2, 1e-3, "total contact force = p pi R^2 (N)")
pr = read_csv(out + "/probes.csv")
gaps = [-pr["n%d_uy" % k][-1] for k in range(5)]
print("  penetration under the nodes r = 0, 0.25, ..., 1: " + ", ".join("%.4e" % g for g in gaps))
close(gaps[0], p / c, 1e-4, "the axis node penetrates p / c_N like the others (mm)")
for k in range(1, 5):
    close(gaps[k], p / c, 1e-4, "node at r = %.2f penetrates p / c_N (mm)" % (0.25 * k))
ct = read_csv(out + "/contact.csv")
close(ct["sliding_max_penetration"][-1], max(gaps), 1e-6,
      "contact.csv's maximum penetration is the largest of the nodes' (mm)")

# 4. The exchange through a disc pressed on a tool at 400 K, over one step of
# 1 us (the surface warms by ~1e-3 K: the exchange is h A (T0 - T_tool)).
h = 150 * (p / 932.0) ** 0.95
dt, T0, T_tool = 1e-6, 300.0, 400.0
out, s, _ = run("tests/contact_block.prm", [
    "Mechanics/Two-dimensional model=axisymmetric", "Time/End time=%g" % dt, "Time/Time step=%g" % dt,
    "Boundary conditions/Displacement=", "Boundary conditions/Pressure=top: %g" % p,
    "Contact/sliding/Friction coefficient=0", "Contact/sliding/Penalty per=area",
    "Contact/sliding/Penalty normal=%g" % c, "Contact/sliding/Penalty tangent=%g" % c,
    "Contact/sliding/Thermal/Conductance=150", "Contact/sliding/Thermal/Hardness=932",
    "Contact/sliding/Thermal/Exponent=0.95", "Contact/floor/Temperature=%g" % T_tool,
    "Physics/Coupling=isothermal split", "Heat/Initial temperature=%g" % T0,
    "Bodies/block/Material/Elasticity/Density=2.7e-9", "Bodies/block/Material/Elasticity/Heat capacity=0.9e9",
    "Bodies/block/Material/Thermal/Conductivity=150"], name="contact_axis_conduction")
ct = read_csv(out + "/contact.csv")
exchanged = ct["sliding_heat_exchanged"][-1]
expected = h * math.pi * R ** 2 * (T0 - T_tool) * dt
print("  heat exchanged in the first 1 us: %.6e mJ, h pi R^2 (T0 - T_tool) dt = %.6e mJ" % (exchanged, expected))
close(exchanged, expected, 1e-3, "heat exchanged with the tool = h0 (p/H)^e pi R^2 (T0 - T_tool) dt (mJ)")
finish()

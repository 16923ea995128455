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
finish()

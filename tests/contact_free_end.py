"""A slave node just beyond the free end of its master surface
(tests/contact_free_end.prm; doc/contact.md, "Free ends"): the end segment,
extended, carries it with its force tapered to zero over 0.05 segments past
the parameter tolerance (0.001), so the force is continuous there and Newton
does not flip the node in and out of contact (the tube's cut-backs,
doc/tube_impact.md).

Independent answers:
- the assembled tangent against central differences of the residual
  (Mechanics/Newton/Check tangent) at every iteration but the first (there
  the nodes sit at g = 0, the kink of the penalty): the taper's derivative
  through the projection is in it;
- the geometry: the upper block shifted by 0.005 mm puts its bottom right node
  0.02 segments beyond the lower block's top, inside the taper: 5 active
  nodes; shifted by 0.015 mm (0.06 segments, beyond the taper): 4;
- equilibrium: the contact's normal forces carry the 10 MPa x 1 mm = 10 N of
  the pressure (to the friction's and the normals' small tilt).
"""
import re
from anvil_test import run, check, finish

for shift, active in ((0.005, 5), (0.015, 4)):
    blocks = "Geometry/Blocks=lower: 0, 0, 1, 1, 4, 4; upper: %g, 1, %g, 1.5, 4, 2" % (shift, 1 + shift)
    out, s, stdout = run("tests/contact_free_end.prm", [blocks, "Mechanics/Newton/Check tangent=true",
                                                        "Output/Verbosity=normal"],
                         name="contact_free_end_%g" % shift)
    errors, first = [], True
    for line in stdout.splitlines():
        m = re.search(r"tangent check: \|K du - FD\| / \|K du\| = (\S+)", line)
        if m:
            if not first:
                errors.append(float(m.group(1)))
            first = False
    q = s["quantities_of_interest"]
    print("  shift %g mm (%.3f segments beyond the end): %d active nodes, normal force %.6f N, "
          "worst FD error %.2e over %d checks, Newton %d / %d steps, cut-backs %d"
          % (shift, shift / 0.25, q["active"], q["N"], max(errors), len(errors), s["newton_iterations"],
             s["steps"], s["cut_backs"]))
    check(q["active"] == active, "shift %g: %d active nodes (expected %d)" % (shift, q["active"], active))
    check(len(errors) > 0 and max(errors) < 1e-6, "shift %g: tangent matches central differences (%.2e < 1e-6)"
          % (shift, max(errors)))
    check(abs(q["N"] - 10) < 1e-4 * 10, "shift %g: normal forces %.6f N carry the 10 N load" % (shift, q["N"]))
    check(s["cut_backs"] == 0, "shift %g: no cut-back" % shift)
finish()

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

3D (tests/contact_free_end_3d.prm, the blocks 1 mm deep, 4 x 4 facets): the
same beyond a free facet edge (the edge x = 1 of the lower block's top): 25
active nodes at 0.02 facets beyond it, 20 at 0.06; 10 MPa x 1 mm^2 = 10 N
carried; Newton converges quadratically (at most 4 iterations a step, no
cut-back). The element's tangent with the taper's derivative is checked
against central differences in tests/contact_element.cc (part 9): the
scene-level check reports 1e-3..7e-3 in 3D from the second step on, with or
without the taper (also on main, sharp edges; the element-level check, and
Newton's quadratic convergence, say the contact tangent is right), so it is
asserted in 2D only.
"""
import re
from anvil_test import run, check, finish

CASES = [(2, shift, active, "Geometry/Blocks=lower: 0, 0, 1, 1, 4, 4; upper: %g, 1, %g, 1.5, 4, 2"
          % (shift, 1 + shift)) for shift, active in ((0.005, 5), (0.015, 4))] + \
        [(3, shift, active, "Geometry/Blocks=lower: 0, 0, 0, 1, 1, 1, 4, 4, 4; upper: %g, 1, 0, %g, 1.5, 1, 4, 2, 4"
          % (shift, 1 + shift)) for shift, active in ((0.005, 25), (0.015, 20))]
for dim, shift, active, blocks in CASES:
    scene = "tests/contact_free_end.prm" if dim == 2 else "tests/contact_free_end_3d.prm"
    out, s, stdout = run(scene, [blocks, "Mechanics/Newton/Check tangent=true", "Output/Verbosity=normal"],
                         name="contact_free_end_%dd_%g" % (dim, shift))
    errors, first = [], True
    for line in stdout.splitlines():
        m = re.search(r"tangent check: \|K du - FD\| / \|K du\| = (\S+)", line)
        if m:
            if not first:
                errors.append(float(m.group(1)))
            first = False
    q = s["quantities_of_interest"]
    print("  %dD, shift %g mm (%.3f segments beyond the end): %d active nodes, normal force %.6f N, "
          "worst FD error %.2e over %d checks, Newton %d / %d steps, cut-backs %d"
          % (dim, shift, shift / 0.25, q["active"], q["N"], max(errors), len(errors), s["newton_iterations"],
             s["steps"], s["cut_backs"]))
    check(q["active"] == active, "%dD, shift %g: %d active nodes (expected %d)" % (dim, shift, q["active"], active))
    if dim == 2:
        check(len(errors) > 0 and max(errors) < 1e-6, "%dD, shift %g: tangent matches central differences (%.2e < 1e-6)"
              % (dim, shift, max(errors)))
    else:
        per_step = [int(x) for x in re.findall(r"Newton +(\d+) \|R\|", stdout)]
        check(len(per_step) == s["steps"] and max(per_step) <= 4,
              "%dD, shift %g: Newton converges quadratically (iterations per step %s)" % (dim, shift, per_step))
    check(abs(q["N"] - 10) < 1e-4 * 10, "%dD, shift %g: normal forces %.6f N carry the 10 N load" % (dim, shift, q["N"]))
    check(s["cut_backs"] == 0, "%dD, shift %g: no cut-back" % (dim, shift))
# 3D, the sharp edge (Free end taper = 0): the last row is not carried.
out, s, _ = run("tests/contact_free_end_3d.prm", ["Contact/interface/Free end taper=0"],
                name="contact_free_end_3d_sharp")
check(s["quantities_of_interest"]["active"] == 20,
      "3D, shift 0.005, sharp edge: %d active nodes (expected 20: the taper carries the last row)"
      % s["quantities_of_interest"]["active"])
finish()

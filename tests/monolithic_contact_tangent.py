"""The monolithic scheme's coupled tangent with thermomechanical contact
against central finite differences of the coupled residual
(Physics/Monolithic check tangent), in the geometries monolithic_contact.py
(plane strain, two_blocks) does not cover: axisymmetric and 3D, a deformable
master (node-to-segment / node-to-facet, Coulomb friction, conductance
h0 (p/H)^e of eq. 34, frictional heat of eq. 31-33) and a rigid tool (its
conductance to the tool's temperature writes the slave node's row: K_Tu
through the pressure and the node's area, K_TT through h A).

Each scene presses, then slides (axisymmetric: the top is stretched
radially, so the contact slips in proportion to r); one side is held at
400 K against 300 K so the conductance carries heat and its dependence on
the pressure is visible in K_Tu; thermal expansion puts the temperature into
the mechanics (K_uT). The first iteration of a step after a plastic one is
left out (kink of the return map, as in monolithic_tangent.py).

Printed per case: the worst |J v - FD| / |FD| (both block rows), the cross
blocks' share of the temperature rows' J v (a missing or mis-coloured contact
term would show as an error of that size), and the Newton contraction orders
of the converged steps."""
import re
from anvil_test import run, check, finish

# Table 1 data with expansion on both bodies, Table 2's surface.
EXPANSION = ["Bodies/%s/Material/Elasticity/Thermal expansion=23.86e-6" % b for b in ("upper", "lower")]
# Two blocks (prm/two_blocks.prm's materials and pair), 0.5 mm thick, small
# meshes; the upper one's top at 400 K, pressed over 1 ms, then driven.
BLOCKS = EXPANSION + [
    "Physics/Coupling=monolithic", "Physics/Monolithic tolerance=1e-10",
    "Output/Field interval=0", "Output/Figure list=", "Output/Quantities of interest=",
    "Time/Time step=1e-3", "Time/End time=4e-3",
    "Heat/Boundary conditions/Temperature=upper.top: 400",
    "Boundary conditions/Pressure=upper.top: 10*min(t/1e-3, 1)"]
PRESS_2D = "lower.bottom: ux = 0, uy = 0; upper.top: "
# A block on a rigid floor at 400 K (tests/contact_block.prm), J2 with Table 1's
# data, penalties c_N = c_T = 1e3 N/mm per node as the seed's (the penetration,
# ~1e-3 mm, far above the difference steps; see doc/monolithic.md on stiffer ones).
BLOCK = ["Bodies/block/Material/Model=J2",
         "Contact/sliding/Penalty normal=1e3", "Contact/sliding/Penalty tangent=1e3",
         "Bodies/block/Material/Elasticity/Density=2.7e-9",
         "Bodies/block/Material/Elasticity/Heat capacity=0.9e9",
         "Bodies/block/Material/Elasticity/Thermal expansion=23.86e-6",
         "Bodies/block/Material/Elasticity/Reference temperature=300",
         "Bodies/block/Material/Hardening/Initial yield stress=50",
         "Bodies/block/Material/Hardening/Hardening modulus=50",
         "Bodies/block/Material/Thermal/Conductivity=150",
         "Contact/sliding/Thermal/Conductance=150", "Contact/sliding/Thermal/Hardness=932",
         "Contact/sliding/Thermal/Exponent=0.95", "Contact/floor/Temperature=400",
         "Heat/Initial temperature=300",
         "Physics/Coupling=monolithic", "Physics/Monolithic tolerance=1e-10",
         "Output/Quantities of interest=", "Output/Probes=",
         "Time/Time step=0.25", "Time/End time=1.75"]
cases = [
    ("axisymmetric, deformable master", "prm/two_blocks.prm", BLOCKS + [
        "Mechanics/Two-dimensional model=axisymmetric",
        # The upper block on the axis: its axis node is a slave node.
        "Geometry/Blocks=lower: 0, 0, 2, 0.5, 6, 2; upper: 0, 0.5, 1, 1, 4, 2",
        "Boundary conditions/Displacement=" + PRESS_2D + "ux = 0.01*x*max(t - 1e-3, 0)/1e-3"]),
    ("3D, deformable master", "prm/two_blocks.prm", BLOCKS + [
        "Dimension=3",
        # Non-matching facets, no slave node on a master edge (where the
        # closest facet switches: a kink); the upper block inside the lower's top.
        "Geometry/Blocks=lower: 0, 0, 0, 2, 0.5, 1, 4, 1, 2; upper: 0.3, 0.5, 0.3, 1.2, 1, 0.7, 3, 1, 3",
        "Boundary conditions/Displacement=lower.bottom: ux = 0, uy = 0, uz = 0; "
        "upper.top: ux = 0.02*max(t - 1e-3, 0)/1e-3, uz = 0"]),
    ("plane strain, rigid tool", "tests/contact_block.prm", BLOCK + [
        "Boundary conditions/Displacement=top: ux = 0.05*max(t - 1, 0)"]),
    ("axisymmetric, rigid tool", "tests/contact_block.prm", BLOCK + [
        "Mechanics/Two-dimensional model=axisymmetric", "Contact/sliding/Penalty per=area",
        "Contact/sliding/Penalty normal=1e4", "Contact/sliding/Penalty tangent=1e4",
        "Boundary conditions/Displacement=top: ux = 0.01*x*max(t - 1, 0)"]),
    ("3D, rigid tool", "tests/contact_block.prm", BLOCK + [
        "Dimension=3", "Geometry/Blocks=block: 0, 0, 0, 1, 1, 1, 3, 3, 3", "Contact/floor/Point=0, 0, 0",
        "Contact/floor/Normal=0, 1, 0", "Boundary conditions/Displacement=top: ux = 0.05*max(t - 1, 0), uz = 0"]),
]
for name, scene, sets in cases:
    tag = re.sub("[^a-z0-9]+", "_", name.lower())
    out, s, stdout = run(scene, sets + ["Physics/Monolithic check tangent=true", "Output/Verbosity=normal"],
                         name="monolithic_contact_tangent_" + tag)
    errors, shares, orders, first = [], [], [], True
    for line in stdout.splitlines():
        m = re.search(r"coupled tangent check: \|J v - FD\| / \|FD\| = (\S+) \(displacement rows (\S+), "
                      r"temperature rows (\S+)\); cross-block share of J v: (\S+) \(displacement rows\), (\S+)",
                      line)
        if m:
            if not first or not errors:
                errors.append(tuple(float(m.group(k)) for k in (1, 2, 3)))
                shares.append(float(m.group(5)))
            first = False
        elif line.startswith("step"):
            first = True
        m = re.search(r"monolithic +\d+: .*order (\S+)", line)
        if m:
            orders.append(float(m.group(1)))
    worst = max(e[0] for e in errors) if errors else 1.0
    print("  %-32s %2d checks, worst |Jv - FD|/|FD| %.2e (u rows %.2e, T rows %.2e); cross-block share of "
          "the T rows' J v up to %.2e; Newton %d its / %d steps; orders %s"
          % (name, len(errors), worst, max(e[1] for e in errors) if errors else 1,
             max(e[2] for e in errors) if errors else 1, max(shares) if shares else 0,
             s["newton_iterations"], s["steps"], " ".join("%.2f" % o for o in orders)))
    check(len(errors) > 0 and worst < 1e-5, "%s: coupled tangent with contact matches finite differences (%.2e)"
          % (name, worst))
    # The check means something only if the cross blocks carry a share far above its error.
    check(shares and max(shares) > 1e3 * worst, "%s: cross blocks carry %.1e of J v, >> the error"
          % (name, max(shares) if shares else 0))
    check(s["cut_backs"] == 0, "%s: no cut-back" % name)
finish()

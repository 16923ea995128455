"""The energy audit's elastic energy summed at the audit's points
(the audit's terms, from the step's last evaluation or compute_step_audit's
pass: W = p^2/2K(T) + s:s/4G(T) at the points' stresses and
temperatures, times J dV as the audit computes them) against the same
integral by FEValues on the displacement (elastic_strain_energy(), the route
used before): with ANVIL_AUDIT_CHECK set, every accepted step prints both,
and the run stops if they differ by more than 1e-12 relative.

Every W J dV is >= 0, so the two sums may differ by their terms' round-off
alone (J from two evaluations of the same F, dV with or without the ring
factor folded in): expected <= 1e-15 relative, bound 1e-12. Scenes: the tube
(axisymmetric, F-bar, dynamic, adiabatic heat), the thermal necking bar
(axisymmetric, a heat field), two blocks (plane strain, contact, heat), the
twisted bar (3D)."""
import os
import re

from anvil_test import run, check, finish

CASES = [("prm/tube_impact.prm", ["Time/End time=1e-4"]),
         ("prm/necking_bar_thermal.prm", ["Time/End time=0.5"]),
         ("prm/two_blocks.prm", ["Time/End time=1e-3"]),
         ("prm/twisted_bar_3d.prm", [])]
os.environ["ANVIL_AUDIT_CHECK"] = "1"
for scene, sets in CASES:
    name = os.path.splitext(os.path.basename(scene))[0]
    out, summary, stdout = run(scene, sets + ["Output/Field interval=0"], name="audit_state_" + name)
    pairs = [(float(a), float(b)) for a, b in re.findall(
        r"ANVIL_AUDIT_CHECK elastic energy: points (\S+) FEValues (\S+) N mm", stdout)]
    worst = max(abs(a - b) / abs(b) if b else abs(a) for a, b in pairs) if pairs else float("nan")
    largest = max(b for _, b in pairs) if pairs else 0
    steps = summary.get("steps")
    print("  %s: %d steps compared, elastic energy up to %.6g N mm, largest relative difference %.1e"
          % (name, len(pairs), largest, worst))
    check(len(pairs) > 0 and len(pairs) == steps and largest > 0,
          name + ": a stressed state, compared at every step (%s steps)" % steps)
    check(worst <= 1e-12, name + ": points = FEValues within 1e-12 relative")
finish()

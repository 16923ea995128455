"""The monolithic scheme with thermomechanical contact (doc/monolithic.md,
"Contact"), on the seed's two blocks (prm/two_blocks.prm: node-to-segment
Coulomb friction, conductance h0 (p/H)^e, eq. 34, frictional heat eq. 31-33).

1. The coupled tangent against central finite differences of the coupled
   residual, in a fixed direction of both fields, at every Newton iteration of
   the pressing and the first sliding steps (Physics/Monolithic check
   tangent): the contact's conductance through the pressure and its
   frictional power through the slip enter K_Tu, the exchange's
   temperatures K_TT. Without the contact links in the colouring (a slave
   node and its master face share no cell) the slave-master terms of K_Tu
   would be missing or mixed between columns: an error of the cross block's
   share, printed beside.
2. Equal to the converged iterated staggered answer (backward Euler heat
   steps, one per mechanical step, tight Staggered tolerance) over the
   pressing and part of the slide: the blocks' mean temperatures, the
   friction work and the contact heat, to the iteration tolerance."""
import re
import sys
from anvil_test import run, read_csv, check, close, finish

SHORT = ["Output/Field interval=0", "Time/End time=%s" % (sys.argv[1] if len(sys.argv) > 1 else "6e-4"),
         "Output/Figure list="]

# --- 1. coupled tangent against finite differences
out, s, stdout = run("prm/two_blocks.prm", SHORT + [
    "Physics/Coupling=monolithic", "Physics/Monolithic tolerance=1e-10",
    "Physics/Monolithic check tangent=true", "Output/Verbosity=normal"], name="monolithic_contact_tangent")
errors, shares = [], []
for line in stdout.splitlines():
    m = re.search(r"coupled tangent check: \|J v - FD\| / \|FD\| = (\S+) \(displacement rows (\S+), "
                  r"temperature rows (\S+)\); cross-block share of J v: (\S+) \(displacement rows\), (\S+)", line)
    if m:
        errors.append(tuple(float(m.group(k)) for k in (1, 2, 3)))
        shares.append(float(m.group(5)))
worst = max(e[0] for e in errors) if errors else 1.0
print("  tangent: %d checks, worst |Jv - FD|/|FD| %.2e (u rows %.2e, T rows %.2e); cross-block share of the "
      "temperature rows' J v up to %.2e; Newton %d its / %d steps"
      % (len(errors), worst, max(e[1] for e in errors) if errors else 1, max(e[2] for e in errors) if errors else 1,
         max(shares) if shares else 0, s["newton_iterations"], s["steps"]))
check(len(errors) > 0 and worst < 1e-5, "two blocks: coupled tangent with contact matches finite differences (%.2e)"
      % worst)
check(s["cut_backs"] == 0, "two blocks (monolithic): no cut-back")
finish()

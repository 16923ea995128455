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
   friction work and the contact heat, to the iteration tolerance.
3. The iterative linear solver (GMRES + one AMG per diagonal block) forced
   gives the direct solver's answer to the Newton tolerance."""
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

# --- 2. equal to the converged iterated staggered answer
COMMON = ["Output/Field interval=0", "Output/Figure list=", "Time/End time=1.5e-3",
          "Mechanics/Newton/Residual tolerance=1e-11", "Mechanics/Newton/Absolute residual tolerance=1e-9",
          "Heat/Time integration/Method=backward Euler", "Heat/Time integration/Fixed step size=1e9"]
mono, sm, _ = run("prm/two_blocks.prm", COMMON + ["Physics/Coupling=monolithic", "Physics/Monolithic tolerance=1e-10"],
                  name="monolithic_contact_two_blocks")
stag, ss, _ = run("prm/two_blocks.prm", COMMON + [
    "Physics/Coupling=iterated staggered", "Physics/Staggered tolerance=1e-9", "Physics/Staggered iterations=100",
    "Heat/Time integration/Relative tolerance=1e-13", "Heat/Time integration/Absolute tolerance=1e-13"],
    name="monolithic_contact_two_blocks_staggered")
check(sm["steps"] == ss["steps"], "same steps (%d, %d)" % (sm["steps"], ss["steps"]))
qm, qs = sm["quantities_of_interest"], ss["quantities_of_interest"]
for k in ("delta_T_upper", "delta_T_lower", "friction_work"):
    print("  %-14s monolithic %.12g, iterated staggered %.12g (relative difference %.2e)"
          % (k, qm[k], qs[k], abs(qm[k] - qs[k]) / abs(qs[k])))
    close(qm[k], qs[k], 1e-7, "two blocks %s: monolithic = iterated staggered" % k)
for k in ("contact_heat", "heat_content_change"):
    close(sm["heat"][k], ss["heat"][k], 1e-7, "two blocks %s: monolithic = iterated staggered" % k)
a, b = read_csv(mono + "/energy.csv"), read_csv(stag + "/energy.csv")
for c in a:
    # The *_error columns measure round-off (balances that close to ~1e-12): left out.
    if c in b and c not in ("step", "time") and "error" not in c:
        scale = max(abs(x) for x in b[c]) or 1.0
        worst = max(abs(x - y) for x, y in zip(a[c], b[c]))
        check(worst <= 1e-7 * scale or worst < 1e-12, "energy.csv %s: equal to %.1e of its scale" % (c, worst / scale))
print("  wall time: monolithic %.1f s (%d Newton its), iterated staggered %.1f s (%d Newton its)"
      % (sm.get("wall_time", 0), sm["newton_iterations"], ss.get("wall_time", 0), ss["newton_iterations"]))

# --- 3. GMRES + block AMG against KLU
SOLVER = ["Output/Field interval=0", "Output/Figure list=", "Time/End time=4e-4",
          "Physics/Coupling=monolithic", "Physics/Monolithic tolerance=1e-10"]
_, sd, _ = run("prm/two_blocks.prm", SOLVER + ["Physics/Monolithic linear solver=direct"],
               name="monolithic_contact_direct")
_, si, _ = run("prm/two_blocks.prm", SOLVER + ["Physics/Monolithic linear solver=iterative"],
               name="monolithic_contact_iterative")
print("  linear iterations: direct %d, iterative %d" % (sd["linear_iterations"], si["linear_iterations"]))
for k in ("delta_T_upper", "delta_T_lower", "friction_work"):
    close(si["quantities_of_interest"][k], sd["quantities_of_interest"][k], 1e-8,
          "two blocks %s: iterative = direct linear solver" % k)
finish()

"""The monolithic scheme's coupled tangent [K_uu K_uT; K_Tu K_TT] against
central finite differences of the coupled residual (R_u, R_T), in a fixed
direction of both fields, at every Newton iteration of a plastic, heated,
thermally softening and expanding block: plane strain, axisymmetric and 3D
(Physics/Monolithic check tangent). Then the Newton iteration converges
quadratically: e_k+1 / e_k^2 of the normalised residual e (printed by the
scheme with the contraction order) stays bounded (< 10) from e_k < 1e-2 down
to the round-off floor (e ~ 1e-13); a linear rate would make it grow without
bound. (The first iterate is the mechanics converged at T_n, so e_0 = 1 is
the heat's residual alone and the first order printed is not asymptotic.)
The check also prints the cross blocks' share of J v: a missing cross block
would show as an error of that size, 1e-3 to 1e-2 here.

The first iteration of a step after a plastic one is left out of the tangent
check (as in global_tangent.py): there the yielded points sit exactly on the
kink between elastic unloading and plastic loading, where the residual has no
derivative."""
import re
from anvil_test import run, check, finish

HEAT = ["Physics/Coupling=monolithic", "Physics/Monolithic tolerance=1e-10",
        "Heat/Initial temperature=293",
        "Bodies/body/Material/Elasticity/Thermal expansion=5e-5",
        "Bodies/body/Material/Elasticity/Taylor-Quinney coefficient=0.9",
        "Bodies/body/Material/Hardening/Thermal softening/Model=linear",
        "Bodies/body/Material/Hardening/Thermal softening/Softening coefficient=2e-3",
        "Bodies/body/Material/Hardening/Thermal softening/Reference temperature=293",
        # Slow enough for conduction to matter, fast enough to heat by tens of K.
        "Time/End time=0.01", "Time/Time step=0.0025",
        "Heat/Boundary conditions/Convection=bottom: 0.5, 293"]
BLOCK_3D = ["Dimension=3", "Geometry/Blocks=body: 0, 0, 0, 1, 1, 1, 3, 3, 3",
            "Boundary conditions/Displacement=bottom: ux = 0, uy = 0, uz = 0; "
            "top: ux = 0.05*t/0.01, uy = -0.1*t/0.01, uz = 0.02*t/0.01",
            "Boundary conditions/Pressure=right: 50*t/0.01"]
BLOCK_2D = ["Boundary conditions/Displacement=bottom: ux = 0, uy = 0; top: ux = 0.05*t/0.01, uy = -0.1*t/0.01",
            "Boundary conditions/Pressure=right: 50*t/0.01"]
cases = [
    ("plane strain, F-bar", BLOCK_2D),
    ("axisymmetric, F-bar", BLOCK_2D + ["Mechanics/Two-dimensional model=axisymmetric"]),
    ("3D, F-bar", BLOCK_3D),
]
for name, sets in cases:
    tag = re.sub("[^a-z0-9]+", "_", name.lower())
    out, s, stdout = run("tests/plastic_block.prm", HEAT + sets + ["Physics/Monolithic check tangent=true",
                                                                    "Output/Verbosity=normal"],
                         name="monolithic_tangent_" + tag)
    errors, orders, constants, first = [], [], [], True
    for line in stdout.splitlines():
        m = re.search(r"coupled tangent check: \|J v - FD\| / \|FD\| = (\S+) \(displacement rows (\S+), "
                      r"temperature rows (\S+)\)", line)
        if m:
            if not first or not errors:
                errors.append((float(m.group(1)), float(m.group(2)), float(m.group(3))))
            first = False
        elif line.startswith("step"):
            first = True
        m = re.search(r"monolithic +\d+: .*\((\S+) of .*\((\S+) of .*e/e_prev\^2 ([^, ]+)", line)
        if m:
            e = max(float(m.group(1)), float(m.group(2)))
            if 1e-11 < e and e / float(m.group(3)) < 1e-4:  # e_prev^2 = e / C < 1e-4
                constants.append(float(m.group(3)))
        m = re.search(r"monolithic +\d+: .*order (\S+)", line)
        if m:
            orders.append(float(m.group(1)))
    worst = max(e[0] for e in errors) if errors else 1.0
    print("  %-22s %2d checks, worst |Jv - FD|/|FD| %.2e (u rows %.2e, T rows %.2e); Newton %d its / %d steps; "
          "orders %s; e_k+1/e_k^2 %s" % (name, len(errors), worst, max(e[1] for e in errors) if errors else 1,
                                         max(e[2] for e in errors) if errors else 1, s["newton_iterations"],
                                         s["steps"], " ".join("%.2f" % o for o in orders),
                                         " ".join("%.2g" % c for c in constants)))
    check(len(errors) > 0 and worst < 1e-5, "%s: coupled tangent matches finite differences (%.2e)" % (name, worst))
    check(s["cut_backs"] == 0, "%s: no cut-back" % name)
    check(len(constants) > 0 and max(constants) < 10,
          "%s: quadratic convergence (e_k+1/e_k^2 at most %.2g)" % (name, max(constants) if constants else 0))
finish()

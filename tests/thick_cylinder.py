"""Axisymmetric thick-walled cylinder (a = 10, b = 20 mm, axial displacement
held) under internal pressure, prm/thick_cylinder.prm:

 - elastic (p = 10 MPa): radial displacements at the bore and outside against
   Lame's solution u(r) = (1 + nu) p a^2 / (E (b^2 - a^2)) ((1 - 2 nu) r + b^2 / r);
 - elastic-perfectly plastic: the plastic front radius c against Hill's
   closed form p = 2 s0/sqrt(3) (ln(c/a) + (b^2 - c^2)/(2 b^2)) for every load
   step past first yield (the closed form takes sigma_z as the mean of the
   in-plane stresses, exact for an incompressible material; nu = 0.3 here);
 - first yield at p_y = s0/sqrt(3) (1 - a^2/b^2)."""
import math
from anvil_test import run, read_csv, check, close, finish

a, b, E, nu, s0 = 10.0, 20.0, 200000.0, 0.3, 300.0
# Elastic
p = 10.0
out, s, _ = run("prm/thick_cylinder.prm", ["Boundary conditions/Pressure=left: %g*t" % p, "Time/Time step=1"],
                name="cylinder_elastic")
lame = lambda r: (1 + nu) * p * a * a / (E * (b * b - a * a)) * ((1 - 2 * nu) * r + b * b / r)
q = s["quantities_of_interest"]
close(q["bore_ur"], lame(a), 2e-3, "Lame: radial displacement at the bore (mm)")
close(q["outside_ur"], lame(b), 2e-3, "Lame: radial displacement outside (mm)")

# Elastic-plastic: probes at the cell centres along the radius.
n = 40
radii = [a + (k + 0.5) * (b - a) / n for k in range(n)]
probes = "; ".join("r%d: %.6f, 0.5" % (k, r) for k, r in enumerate(radii))
out, s, _ = run("prm/thick_cylinder.prm", ["Output/Probes=" + probes, "Output/Quantities of interest="],
                name="cylinder_plastic")
h = read_csv(out + "/probes.csv")
k_y = 2 * s0 / math.sqrt(3)
p_y = s0 / math.sqrt(3) * (1 - a * a / (b * b))
hill = lambda c: k_y * (math.log(c / a) + (b * b - c * c) / (2 * b * b))
worst = 0
print("   p (MPa)   front (mm)   Hill (mm)")
for i, t in enumerate(h["time"]):
    p = 220 * t
    plastic = [r for k, r in enumerate(radii) if h["r%d_equivalent_plastic_strain" % k][i] > 0]
    if p < p_y:
        check(not plastic, "p = %.1f MPa < p_y = %.1f MPa: elastic everywhere" % (p, p_y))
        continue
    lo, hi = a, b  # Hill's front by bisection
    for _ in range(100):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if hill(mid) < p else (lo, mid)
    c = 0.5 * (lo + hi)
    front = max(plastic) + 0.5 * (b - a) / n if plastic else a
    worst = max(worst, abs(front - c))
    print("   %7.1f   %10.3f   %9.3f" % (p, front, c))
check(worst <= (b - a) / n, "plastic front within one cell of Hill's solution (worst %.3f mm, cell %.3f mm)"
      % (worst, (b - a) / n))
check(s["cut_backs"] == 0, "no cut-back up to 92 % of the collapse pressure")
print("  Newton iterations per step: %.2f" % (s["newton_iterations"] / s["steps"]))
finish()

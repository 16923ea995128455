"""Necking of a circular bar (prm/necking_bar.prm, Simo & Miehe 1992 geometry,
isothermal, axisymmetric F-bar Q1) on three meshes (5 x 20, 10 x 40,
20 x 80 cells for the half bar):

 - the load-elongation curve has its maximum (then falls by > 30 %);
 - the neck forms at the imperfection: the radius shrinks most at mid-length,
   the ends barely (their plastic strain stays near uniform);
 - the answer converges under refinement: the differences of the final neck
   radius and of the maximum load between successive meshes decrease;
 - Newton: mean iterations per step at the default tolerance (<= 6, printed)."""
import math
from anvil_test import run, read_csv, check, finish

rows = []
for n in (1, 2, 4):
    out, s, _ = run("prm/necking_bar.prm", ["Geometry/Radial cells=%d" % (5 * n), "Geometry/Axial cells=%d" % (20 * n),
                                            "Output/Field interval=0", "Output/Verbosity=quiet"], name="necking_%d" % n)
    r = read_csv(out + "/reactions.csv")
    F, t = r["top_Fy"], r["time"]
    i_max = F.index(max(F))
    q = s["quantities_of_interest"]
    rows.append(dict(cells="%d x %d" % (5 * n, 20 * n), F_max=max(F) / 1000, u_max=7 * t[i_max], F_end=F[-1] / 1000,
                     neck=6.2975 + q["neck_radius_change"], end=6.413 + q["end_radius_change"],
                     its=s["newton_iterations"] / s["steps"], steps=s["steps"], cut=s["cut_backs"], wall=s["wall_time"]))
print("  mesh      F_max (kN)  at u (mm)  F_end (kN)  neck r (mm)  end r (mm)  Newton/step  steps  cut-backs  wall (s)")
for x in rows:
    print("  %-8s  %10.3f  %9.2f  %10.3f  %11.4f  %10.4f  %11.2f  %5d  %9d  %8.1f" % (
        x["cells"], x["F_max"], x["u_max"], x["F_end"], x["neck"], x["end"], x["its"], x["steps"], x["cut"], x["wall"]))
for x in rows:
    check(x["F_end"] < 0.7 * x["F_max"] and 0.5 < x["u_max"] < 6.5, "%s: the load passes its maximum and falls" % x["cells"])
    check(x["neck"] < 0.75 * x["end"], "%s: the neck forms at the imperfection (radius %.3f vs %.3f at the end)"
          % (x["cells"], x["neck"], x["end"]))
d_neck = [abs(rows[i + 1]["neck"] - rows[i]["neck"]) for i in range(2)]
d_F = [abs(rows[i + 1]["F_max"] - rows[i]["F_max"]) for i in range(2)]
print("  successive differences: neck radius %.4f, %.4f mm; maximum load %.4f, %.4f kN" % (d_neck[0], d_neck[1], d_F[0], d_F[1]))
check(d_neck[1] < d_neck[0], "final neck radius converges under refinement")
check(d_F[1] < d_F[0], "maximum load converges under refinement")
check(rows[1]["its"] <= 6, "default mesh: %.2f Newton iterations per step (target <= 6)" % rows[1]["its"])
finish()

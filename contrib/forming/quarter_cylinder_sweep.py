#!/usr/bin/env python3
"""The seed's temperature sweep of the quarter-cylinder forming (sec. 4.1,
issue 13) in one command, until the study issue lands:

  contrib/forming/quarter_cylinder_sweep.py BUILD_DIR [T ...]   (default 293 493 693 993)

runs prm/quarter_cylinder_forming.prm at each forming temperature (two at a
time: the machine has two cores), then prints per temperature the rotation of
the free end at the end of the hold and at the end (springback = their
difference), against the closed form of elastic-perfectly plastic pure
bending unloading (doc/quarter_cylinder_forming.md):

  kappa = 1/(R + t/2), kappa_e = 2 s'/(E' t), E' = E(T)/(1 - nu^2),
  s' = 2/sqrt(3) sigma_0(T) (plane-strain yield),
  dkappa = kappa_e (3/2 - (kappa_e/kappa)^2/2) if kappa > kappa_e else kappa,
  springback angle = dkappa * L  (the sheet unloads to M = 0 everywhere).

Not yet: the figures (seed Figs. 4-6) and the largest residual J2 stress."""
import csv
import math
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
SCENE = os.path.join(HERE, "..", "..", "prm", "quarter_cylinder_forming.prm")
L, R, t_sheet, nu = 25 * math.pi ** 2, 50 * math.pi, 1.0, 0.33
E0 = 70000.0
g_table = {293: 1, 493: 0.89, 693: 0.77, 793: 0.71, 993: 0.58}     # as in the scene
s0_table = {293: 145, 493: 90, 693: 15, 793: 5, 993: 1}


def interp(table, T):
    xs = sorted(table)
    T = min(max(T, xs[0]), xs[-1])
    for a, b in zip(xs, xs[1:]):
        if a <= T <= b:
            return table[a] + (table[b] - table[a]) * (T - a) / (b - a)


def closed_form_springback(T):
    Ep = E0 * interp(g_table, T) / (1 - nu ** 2)
    sp = 2 / math.sqrt(3) * interp(s0_table, T)
    kappa, kappa_e = 1 / (R + t_sheet / 2), 2 * sp / (Ep * t_sheet)
    dkappa = kappa_e * (1.5 - 0.5 * (kappa_e / kappa) ** 2) if kappa > kappa_e else kappa
    return math.degrees(dkappa * L)


def temperature_expression(T):
    return "293 + (%g - 293)*if(t < 300, t/300, if(t < 3000, 1, max(0, (3100 - t)/100)))" % T


def tip_rotation(row):
    """Rotation of the free end's section, degrees (tip_bottom -> tip_top)."""
    dx = float(row["tip_top_ux"]) - float(row["tip_bottom_ux"])
    dy = 1 + float(row["tip_top_uy"]) - float(row["tip_bottom_uy"])
    return -math.degrees(math.atan2(dx, dy))


def main():
    build = sys.argv[1] if len(sys.argv) > 1 else "build"
    temps = [float(a) for a in sys.argv[2:]] or [293, 493, 693, 993]
    anvil = os.path.join(build, "anvil")
    os.makedirs("output", exist_ok=True)
    jobs = []
    for i, T in enumerate(temps):
        out = os.path.abspath("output/quarter_cylinder_%d" % T)
        cmd = [anvil, SCENE, "--set", "Physics/Prescribed temperature=" + temperature_expression(T),
               "--set", "Output/Directory=" + out]
        log = open(out + ".log", "w")
        jobs.append((T, out, subprocess.Popen(cmd, stdout=log, stderr=subprocess.STDOUT)))
        if len([j for j in jobs if j[2].poll() is None]) >= 2:
            jobs[-2][2].wait()
    print("%6s %8s %10s %10s %12s %12s %6s" % ("T [K]", "steps", "hold [deg]", "end [deg]",
                                                "springback", "closed form", "ratio"))
    for T, out, p in jobs:
        p.wait()
        # Headers carry units ("time [s]"): columns by the name before " [".
        rows = [{k.split(" [")[0]: v for k, v in r.items()}
                for r in csv.DictReader(open(os.path.join(out, "probes.csv")))]
        hold = [r for r in rows if float(r["time"]) <= 3000][-1]
        a_hold, a_end = tip_rotation(hold), tip_rotation(rows[-1])
        cf = closed_form_springback(T)
        print("%6g %8d %10.3f %10.3f %12.3f %12.3f %6.3f" % (T, int(rows[-1]["step"]), a_hold, a_end,
                                                            a_hold - a_end, cf, (a_hold - a_end) / cf))


if __name__ == "__main__":
    main()

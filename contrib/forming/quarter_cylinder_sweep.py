#!/usr/bin/python3
"""The seed's temperature sweep of the quarter-cylinder forming (sec. 4.1,
issue 13) in one command:

  contrib/forming/quarter_cylinder_sweep.py BUILD_DIR [T ...] [--out DIR] [--jobs N]
                                            [--unload-hot] [--set P=V ...]

(default T: 293 493 693 993; --out: output/quarter_cylinder_sweep). It runs
prm/quarter_cylinder_forming.prm at each forming temperature (--jobs runs at
once, default 2: the machine has two cores) and writes to --out:

  table.md       per temperature: steps, Newton iterations, wall time, the
                 rotation of the free end at the end of the hold and at the
                 end, springback (their difference) against the closed form
                 of elastic-perfectly plastic pure bending unloading of the
                 fully wrapped sheet with the relaxed stress (doc/
                 quarter_cylinder_forming.md), the final mean radius of
                 curvature L / theta_end against the die's, and the largest
                 residual J2 (von Mises) stress;
  shapes.png     the four final configurations in one figure (seed Fig. 4);
  j2_<T>.png     the final J2 stress along the sheet for 493 K and 993 K on
                 the initial configuration, vertical dilatation 15 (Figs. 5-6).

--unload-hot holds the forming temperature during the unloading (the scene
cools while it unloads): the closed form with E(T), sigma_0(T) of the forming
temperature then applies as derived. Needs Debian's numpy, matplotlib, vtk
(/usr/bin/python3)."""
import argparse
import csv
import json
import math
import os
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
SCENE = os.path.normpath(os.path.join(HERE, "..", "..", "prm", "quarter_cylinder_forming.prm"))
L, R, t_sheet, nu = 25 * math.pi ** 2, 50 * math.pi, 1.0, 0.33
E0 = 70000.0
g_table = {293: 1, 493: 0.89, 693: 0.77, 793: 0.71, 993: 0.58}     # as in the scene
s0_table = {293: 145, 493: 90, 693: 15, 793: 5, 993: 1}
eta_table = {293: 10, 493: 60, 693: 300, 793: 300, 993: 30}
m_table = {293: 20, 493: 6.7, 693: 3.3, 793: 2, 993: 2}


def interp(table, T):
    xs = sorted(table)
    T = min(max(T, xs[0]), xs[-1])
    for a, b in zip(xs, xs[1:]):
        if a <= T <= b:
            return table[a] + (table[b] - table[a]) * (T - a) / (b - a)


def overstress_after_hold(T, hold=2700.0):
    """Perzyna overstress left after the hold (seed eq. 14 with n = 1, eq. 18):
    ds/dt = -E (s/eta)^m leaves at most ((m - 1) E t / eta^m)^(-1/(m - 1))."""
    E, eta, m = E0 * interp(g_table, T), interp(eta_table, T), interp(m_table, T)
    return ((m - 1) * E * hold / eta ** m) ** (-1 / (m - 1))


def closed_form_springback(T):
    """Springback angle (deg) of elastic-perfectly plastic pure bending to the
    die's mid-surface curvature, unloaded elastically to M = 0 (doc), with the
    relaxed stress sigma_0(T) + the overstress left after the hold."""
    Ep = E0 * interp(g_table, T) / (1 - nu ** 2)
    sp = 2 / math.sqrt(3) * (interp(s0_table, T) + overstress_after_hold(T))
    kappa, kappa_e = 1 / (R + t_sheet / 2), 2 * sp / (Ep * t_sheet)
    dkappa = kappa_e * (1.5 - 0.5 * (kappa_e / kappa) ** 2) if kappa > kappa_e else kappa
    return math.degrees(dkappa * L)


def temperature_expression(T, unload_hot=False):
    if unload_hot:
        return "293 + (%g - 293)*if(t < 300, t/300, 1)" % T
    return "293 + (%g - 293)*if(t < 300, t/300, if(t < 3000, 1, max(0, (3100 - t)/100)))" % T


def tip_rotation(row):
    """Rotation of the free end's section, degrees (tip_bottom -> tip_top)."""
    dx = float(row["tip_top_ux"]) - float(row["tip_bottom_ux"])
    dy = 1 + float(row["tip_top_uy"]) - float(row["tip_bottom_uy"])
    return -math.degrees(math.atan2(dx, dy))


def read_rows(path):
    # Headers carry units ("time [s]"): columns by the name before " [".
    with open(path) as f:
        return [{k.split(" [")[0]: v for k, v in r.items()} for r in csv.DictReader(f)]


def final_field(out):
    """Points (initial configuration), displacement, von Mises stress and the
    cells of the last solution written."""
    import numpy as np
    import vtk
    from vtk.util.numpy_support import vtk_to_numpy
    with open(os.path.join(out, "solution.pvd")) as f:
        last = [l for l in f if "file=" in l][-1].split('file="')[1].split('"')[0]
    reader = vtk.vtkXMLPUnstructuredGridReader()
    reader.SetFileName(os.path.join(out, last))
    reader.Update()
    grid = reader.GetOutput()
    points = vtk_to_numpy(grid.GetPoints().GetData())[:, :2]
    data = grid.GetPointData()
    u = vtk_to_numpy(data.GetArray("displacement"))[:, :2]
    # Cell averages (each cell's four points carry its value): what the mesh
    # resolves, 2 cells through the thickness; the nodal twin smears them more.
    j2 = vtk_to_numpy(data.GetArray("von_mises"))
    cells = np.array([[grid.GetCell(c).GetPointId(k) for k in range(4)]
                      for c in range(grid.GetNumberOfCells())])
    return points, u, j2, cells


def run_all(args):
    anvil = os.path.join(args.build, "anvil")
    os.makedirs(args.out, exist_ok=True)
    pending, running, results = list(args.temperatures), [], {}
    while pending or running:
        while pending and len(running) < args.jobs:
            T = pending.pop(0)
            out = os.path.abspath(os.path.join(args.out, "T%d" % T))
            cmd = [anvil, SCENE, "--set",
                   "Physics/Prescribed temperature=" + temperature_expression(T, args.unload_hot),
                   "--set", "Output/Directory=" + out, "--set", "Output/Field interval=0"]
            for s in args.set:
                cmd += ["--set", s]
            log = open(out + ".log", "w")
            running.append((T, out, time.time(),
                            subprocess.Popen(cmd, stdout=log, stderr=subprocess.STDOUT)))
        time.sleep(0.2)
        for job in list(running):
            T, out, start, p = job
            if p.poll() is not None:
                running.remove(job)
                results[T] = (out, time.time() - start, p.returncode)
    return results


def evaluate(T, out, wall):
    rows = read_rows(os.path.join(out, "probes.csv"))
    with open(os.path.join(out, "summary.json")) as f:
        summary = json.load(f)
    hold = [r for r in rows if float(r["time"]) <= 3000 * (1 + 1e-12)][-1]
    a_hold, a_end = tip_rotation(hold), tip_rotation(rows[-1])
    points, u, j2, cells = final_field(out)
    cf = closed_form_springback(T)
    return {"T": T, "steps": summary["steps"], "newton": summary["newton_iterations"],
            "cut_backs": summary["cut_backs"], "wall": wall, "hold": a_hold, "end": a_end,
            "springback": a_hold - a_end, "closed_form": cf, "ratio": (a_hold - a_end) / cf,
            "radius": L / math.radians(a_end) if a_end > 0 else float("inf"),
            "j2_max": float(j2.max()),
            # Away from the clamp's corner singularity (the last 10 mm).
            "j2_max_free": float(j2[points[:, 0] < L - 10].max()), "field": (points, u, j2, cells)}


def table(results, unload_hot):
    lines = ["| T (K) | steps | Newton its | cut-backs | wall (s) | tip rotation end of hold | at end "
             "| springback | closed form | ratio | final radius L/θ (mm) | largest residual J2 (MPa) "
             "| same, x < L − 10 mm |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in results:
        lines.append("| %g | %d | %d | %d | %.1f | %.2f° | %.2f° | %.2f° | %.2f° | %.3f | %.0f | %.3g | %.3g |"
                     % (r["T"], r["steps"], r["newton"], r["cut_backs"], r["wall"], r["hold"], r["end"],
                        r["springback"], r["closed_form"], r["ratio"], r["radius"], r["j2_max"],
                        r["j2_max_free"]))
    lines.append("")
    lines.append("J2: cell averages (the shipped mesh has 2 cells through the thickness). Die radius %.1f mm "
                 "(mid-surface %.1f mm). Unloading %s." %
                 (R, R + t_sheet / 2, "at the forming temperature (--unload-hot)" if unload_hot
                  else "while cooling to 293 K (as the scene)"))
    return "\n".join(lines) + "\n"


def figures(results, out):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import matplotlib.tri as mtri
    import numpy as np

    # Seed Fig. 4: the final configurations with the die.
    fig, ax = plt.subplots(figsize=(8.4, 5.2))
    phi = np.linspace(math.pi / 2, math.pi, 200)
    ax.fill(np.r_[L + R * np.cos(phi), L], np.r_[-R + R * np.sin(phi), -R], color="0.85",
            label="die (R = 50π mm)")
    ax.plot([0, L], [0, 0], "k:", lw=1, label="initial sheet")
    for r in results:
        points, u, _, cells = r["field"]
        x = points + u
        bottom = np.abs(points[:, 1]) < 1e-9
        order = np.argsort(points[bottom, 0])
        ax.plot(x[bottom][order, 0], x[bottom][order, 1], lw=1.6,
                label="%g K: springback %.1f°" % (r["T"], r["springback"]))
    ax.set_aspect("equal")
    ax.set_xlabel("x (mm)")
    ax.set_ylabel("y (mm)")
    ax.set_title("Final configurations after unloading (seed Fig. 4)")
    ax.legend(loc="upper left", bbox_to_anchor=(1.02, 1), fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "shapes.png"), dpi=130)
    plt.close(fig)

    # Seed Figs. 5-6: residual J2 on the initial configuration, y x 15.
    for r in results:
        if r["T"] not in (493, 993):
            continue
        points, _, j2, cells = r["field"]
        tri = mtri.Triangulation(points[:, 0], 15 * points[:, 1],
                                 np.r_[cells[:, [0, 1, 2]], cells[:, [0, 2, 3]]])
        fig, ax = plt.subplots(figsize=(10, 2.0))
        m = ax.tripcolor(tri, facecolors=np.r_[j2[cells[:, 0]], j2[cells[:, 0]]], cmap="viridis")
        ax.set_aspect("equal")
        ax.set_xlim(-2, L + 2)
        ax.set_xlabel("x (mm), initial configuration")
        ax.set_ylabel("15 y (mm)")
        ax.set_title("Residual J2 stress after unloading (cell averages), forming at %g K "
                     "(largest %.3g MPa)" % (r["T"], r["j2_max"]), fontsize=10)
        fig.colorbar(m, ax=ax, label="J2 (MPa)", fraction=0.03, pad=0.01, aspect=6)
        fig.tight_layout()
        fig.savefig(os.path.join(out, "j2_%d.png" % r["T"]), dpi=130)
        plt.close(fig)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("build")
    parser.add_argument("temperatures", nargs="*", type=float, default=[293, 493, 693, 993])
    parser.add_argument("--out", default=os.path.join("output", "quarter_cylinder_sweep"))
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--unload-hot", action="store_true")
    parser.add_argument("--set", action="append", default=[])
    args = parser.parse_args()
    runs = run_all(args)
    failed = [T for T, (_, _, rc) in runs.items() if rc != 0]
    if failed:
        sys.exit("quarter_cylinder_sweep: anvil failed at T = %s (logs in %s)" % (failed, args.out))
    results = [evaluate(T, *runs[T][:2]) for T in args.temperatures]
    text = table(results, args.unload_hot)
    with open(os.path.join(args.out, "table.md"), "w") as f:
        f.write(text)
    print(text)
    figures(results, args.out)
    print("quarter_cylinder_sweep: table.md, shapes.png, j2_*.png in " + args.out)


if __name__ == "__main__":
    main()

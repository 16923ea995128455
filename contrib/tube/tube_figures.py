#!/usr/bin/python3
"""The tube impact's figures (seed §4.3, Figs. 9-12; doc/tube_impact.md) from
the three cases' output directories.

    /usr/bin/python3 contrib/tube/tube_figures.py CASE1_DIR CASE2_DIR CASE3_DIR [-o doc/figures]

Each CASE_DIR is an anvil output of prm/tube_impact.prm (tests/tube_crush.py
writes output/tube_crush_case1..3: fields at the start and the end, P's
probe). Writes into the figure directory:
  tube_force.png         drive force against Dz, cases 1-3 (seed Fig. 11):
                         the raw force rings with the elastic waves between
                         folds, so each case is drawn faint and as its mean
                         over a 2 mm window of Dz, with its mean over 0-50 mm
                         and the folding band of doc/tube_impact.md;
  tube_temperature_P.png the temperature at P against time, cases 2 and 3
                         (seed Fig. 12);
  tube_temperature.png   the final temperature field of cases 2 and 3 on one
                         colour scale, and their difference (seed Fig. 10);
  tube_folds.png         the deformed section of case 3 at Dz = 50 mm with
                         its mesh, coloured by the equivalent plastic strain,
                         beside the undeformed outline (seed Fig. 9).
The fields are read with anvil-render's reader (VTK), drawn with matplotlib.
"""
import argparse
import csv
import importlib.machinery
import importlib.util
import os
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

V = 15277.8                       # mm/s, the drive speed
BAND = (10.85, 19.69)             # kN, the folding band (doc/tube_impact.md)
AJ = 16.88                        # kN, Abramowicz & Jones with the effective crushing distance
LABELS = {1: "case 1, mechanical", 2: "case 2, no frictional heat", 3: "case 3, frictional heat"}
COLOURS = {1: "tab:blue", 2: "tab:orange", 3: "tab:green"}


def read_csv(path):
    """Columns by bare name (the ' [unit]' dropped)."""
    with open(path) as f:
        rows = list(csv.reader(f))
    return {h.split(" [", 1)[0]: np.array([float(r[i]) for r in rows[1:]]) for i, h in enumerate(rows[0])}


def renderer():
    """anvil-render as a module (its reader and geometry), from the build."""
    here = os.path.dirname(os.path.abspath(__file__))
    for path in (os.environ.get("ANVIL_RENDER", ""), os.path.join(here, "..", "..", "build", "anvil-render")):
        if path and os.path.exists(path):
            loader = importlib.machinery.SourceFileLoader("anvil_render", path)
            spec = importlib.util.spec_from_loader("anvil_render", loader)
            module = importlib.util.module_from_spec(spec)
            loader.exec_module(module)
            return module
    sys.exit("tube_figures.py: build/anvil-render not found (build anvil, or set ANVIL_RENDER)")


def last_field(render, run, field):
    """Deformed points, quads and nodal values of the run's last field output."""
    t, path = render.records(run)[-1]
    grid = render.read(path)
    xyz, cells, values, _ = render.geometry(grid, field, True, 1.0, -1)
    return t, xyz, cells, values


def force_figure(runs, out):
    fig, ax = plt.subplots(figsize=(7.5, 4.5))
    for case, run in runs.items():
        r = read_csv(os.path.join(run, "reactions.csv"))
        dz = V * r["time"]
        f = -r["top_Fy"] / 1000
        ax.plot(dz, f, color=COLOURS[case], lw=0.4, alpha=0.35)
        # mean over a 2 mm window of Dz: the drive work there / 2 mm
        w = np.concatenate([[0], np.cumsum(0.5 * (f[1:] + f[:-1]) * np.diff(dz))])
        w += 0.5 * f[0] * dz[0]
        centre = np.arange(1, dz[-1] - 1, 0.25)
        smooth = (np.interp(centre + 1, dz, w) - np.interp(centre - 1, dz, w)) / 2
        mean = w[-1] / dz[-1]
        ax.plot(centre, smooth, color=COLOURS[case], lw=1.6,
                label="%s: mean %.2f kN" % (LABELS[case], mean))
    ax.axhspan(*BAND, color="0.85", zorder=0, label="folding band %.1f-%.1f kN (Alexander - A&J hardened)" % BAND)
    ax.axhline(AJ, color="0.4", ls="--", lw=0.8, label="Abramowicz & Jones, effective crush %.1f kN" % AJ)
    ax.axhline(35.34, color="0.4", ls=":", lw=0.8, label="squash load 35.3 kN")
    ax.set_xlabel("Dz, displacement of the driven end [mm]")
    ax.set_ylabel("drive force [kN]")
    ax.set_title("Tube impact: force to drive the end (faint: each step; bold: 2 mm mean)")
    ax.set_xlim(0, 50)
    ax.set_ylim(0, 40)
    ax.legend(fontsize=7, loc="upper right")
    fig.tight_layout()
    fig.savefig(os.path.join(out, "tube_force.png"), dpi=100)
    plt.close(fig)


def temperature_P_figure(runs, out):
    fig, ax = plt.subplots(figsize=(6.5, 4))
    for case in (2, 3):
        p = read_csv(os.path.join(runs[case], "probes.csv"))
        T = p["P_temperature"]
        k = int(np.argmax(T))
        ax.plot(1e3 * p["time"], T, color=COLOURS[case],
                label="%s: peak %.1f K at %.2f ms" % (LABELS[case], T[k], 1e3 * p["time"][k]))
        ax.plot(1e3 * p["time"][k], T[k], "o", color=COLOURS[case], ms=4)
    ax.set_xlabel("time [ms]  (Dz = 15.28 mm per ms)")
    ax.set_ylabel("temperature at P [K]")
    ax.set_title("Temperature at P (inner skin, bottom end)")
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "tube_temperature_P.png"), dpi=100)
    plt.close(fig)


def section(ax, xyz, cells, values, norm, cmap, edges):
    tri = [[c[0], c[1], c[2]] for c in cells] + [[c[0], c[2], c[3]] for c in cells]
    m = ax.tripcolor(xyz[:, 0], xyz[:, 1], tri, values, shading="gouraud", cmap=cmap, norm=norm)
    if edges:
        from matplotlib.collections import PolyCollection
        ax.add_collection(PolyCollection([xyz[c, :2] for c in cells], facecolors="none",
                                         edgecolors=(0.1, 0.1, 0.1, 0.6), linewidths=0.2))
    ax.set_aspect("equal")
    ax.set_xlabel("r [mm]")
    return m


def temperature_figure(render, runs, out):
    data = {case: last_field(render, runs[case], "temperature") for case in (2, 3)}
    lo = min(d[3].min() for d in data.values())
    hi = max(d[3].max() for d in data.values())
    norm = matplotlib.colors.Normalize(lo, hi)
    fig, axes = plt.subplots(1, 3, figsize=(7.5, 6), sharey=True)
    for ax, case in zip(axes, (2, 3)):
        t, xyz, cells, T = data[case]
        m = section(ax, xyz, cells, T, norm, "inferno", False)
        ax.set_title("%s\nDz = %.1f mm, max %.0f K" % (LABELS[case], V * t, T.max()), fontsize=8)
    fig.colorbar(m, ax=axes[:2], orientation="horizontal", fraction=0.05, pad=0.1, label="temperature [K]")
    # case 3 - case 2 node by node (the same mesh; drawn on case 3's shape):
    # where the frictional heat went
    _, xyz, cells, T3 = data[3]
    dT = T3 - data[2][3]
    big = max(abs(dT).max(), 1e-9)
    d = section(axes[2], xyz, cells, dT, matplotlib.colors.Normalize(-big, big), "coolwarm", False)
    axes[2].set_title("case 3 - case 2\n(frictional heat), max %+.1f K" % dT[np.argmax(abs(dT))], fontsize=8)
    fig.colorbar(d, ax=axes[2], orientation="horizontal", fraction=0.05, pad=0.1, label="difference [K]")
    for ax in axes:
        ax.set_xlim(xyz[:, 0].min() - 0.5, xyz[:, 0].max() + 0.5)
        ax.set_ylim(-0.5, xyz[:, 1].max() + 0.5)
    axes[0].set_ylabel("z [mm]")
    fig.suptitle("Final temperature, axisymmetric section (r = radius, z = axis)", fontsize=10)
    fig.savefig(os.path.join(out, "tube_temperature.png"), dpi=100)
    plt.close(fig)


def folds_figure(render, runs, out):
    t, xyz, cells, ep = last_field(render, runs[3], "equivalent_plastic_strain_nodal")
    fig, axes = plt.subplots(1, 2, figsize=(6.5, 6.2), gridspec_kw={"width_ratios": [1, 1.6]})
    ax = axes[0]
    ax.add_patch(plt.Rectangle((24.25, 0), 1.5, 100, color="0.6", label="undeformed"))
    section(ax, xyz, cells, ep, matplotlib.colors.Normalize(0, ep.max()), "viridis", False)
    ax.set_xlim(15, 35)
    ax.set_ylim(-1, 101)
    ax.set_ylabel("z [mm]")
    ax.set_title("undeformed (grey) and\nat Dz = %.1f mm" % (V * t), fontsize=9)
    ax = axes[1]
    m = section(ax, xyz, cells, ep, matplotlib.colors.Normalize(0, ep.max()), "viridis", True)
    ax.set_xlim(17, 33)
    ax.set_ylim(-0.5, 25)
    ax.set_title("lower half, with the mesh (folds touch: self-contact)", fontsize=9)
    fig.colorbar(m, ax=axes, orientation="horizontal", fraction=0.05, pad=0.1,
                 label="equivalent plastic strain [-]")
    fig.suptitle("Case 3, deformed section: concertina folds", fontsize=10)
    fig.savefig(os.path.join(out, "tube_folds.png"), dpi=100)
    plt.close(fig)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("runs", nargs=3, help="output directories of cases 1, 2, 3")
    parser.add_argument("-o", "--output", default="doc/figures")
    a = parser.parse_args()
    runs = dict(zip((1, 2, 3), a.runs))
    for case, run in runs.items():
        if not os.path.exists(os.path.join(run, "reactions.csv")):
            sys.stderr.write("tube_figures.py: %s: no reactions.csv (case %d's output directory expected)\n"
                             % (run, case))
            sys.exit(2)
    os.makedirs(a.output, exist_ok=True)
    render = renderer()
    force_figure(runs, a.output)
    temperature_P_figure(runs, a.output)
    temperature_figure(render, runs, a.output)
    folds_figure(render, runs, a.output)
    for name in ("tube_force", "tube_temperature_P", "tube_temperature", "tube_folds"):
        path = os.path.join(a.output, name + ".png")
        print("%s (%d KB)" % (path, os.path.getsize(path) // 1024))


if __name__ == "__main__":
    main()

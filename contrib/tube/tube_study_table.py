#!/usr/bin/env python3
"""The tube impact's convergence measures for every run of a study
(studies/tube_dt.prm, studies/tube_mesh.prm) or of plain output directories:
mean crush force over Dz 0-50 and 0-20 mm, fold half-length, peak temperature
at P, and the run's cost (summary.json).

    python3 contrib/tube/tube_study_table.py output/study/tube_dt output/study/tube_mesh [RUN_DIR ...]

A study directory contributes its runs/<key>/out (labelled by the entries of
record.json that its ladders set); a RUN_DIR is one anvil output. Prints a
markdown table (doc/studies/tube_convergence.md quotes it). The measures are
those of tests/tube_crush.py: the mean force is the drive work int F v dt /
Dz; the folds are the outward bulges (> 3 mm) of the mid-surface probes
m0..m100 (every mm of the undeformed axis) at the end, the chain from the
impact end; H is half their mean spacing.
"""
import csv
import json
import os
import sys

V = 15277.8
LADDER_KEYS = ("Time/Time step", "Geometry/Radial cells", "Geometry/Axial cells")


def read_csv(path):
    with open(path) as f:
        rows = list(csv.reader(f))
    return {h.split(" [", 1)[0]: [float(r[i]) for r in rows[1:]] for i, h in enumerate(rows[0])}


def mean_force(time, F, a, b):
    """Drive work over Dz in [a, b] / its length, kN (trapezoid; the first step from t = 0)."""
    W = [0.5 * F[0] * V * time[0]]
    for i in range(1, len(time)):
        W.append(W[-1] + 0.5 * (F[i] + F[i - 1]) * V * (time[i] - time[i - 1]))
    idx = [i for i in range(len(time)) if a <= V * time[i] <= b + 1e-9]
    i0, i1 = idx[0], idx[-1]
    w0, z0 = (W[i0], V * time[i0]) if a > 0 else (0.0, 0.0)
    return (W[i1] - w0) / (V * time[i1] - z0) / 1000


def fold_half_length(p):
    ys = [k for k in range(101) if "m%d_ux" % k in p]
    ur = [p["m%d_ux" % k][-1] for k in ys]
    peaks = [j for j in range(1, len(ys) - 1) if ur[j] > ur[j - 1] and ur[j] >= ur[j + 1] and ur[j] > 3.0]
    chain = peaks[:2]
    for j in peaks[2:]:
        if j - chain[-1] > 1.5 * (chain[1] - chain[0]):
            break
        chain.append(j)
    if len(chain) < 2:
        return None, []
    return (ys[chain[-1]] - ys[chain[0]]) / (len(chain) - 1) / 2, [ys[j] for j in chain]


def measure(out):
    s = json.load(open(os.path.join(out, "summary.json")))
    r = read_csv(os.path.join(out, "reactions.csv"))
    p = read_csv(os.path.join(out, "probes.csv"))
    time, F = r["time"], [-f for f in r["top_Fy"]]
    m = {"status": s.get("status"), "steps": s.get("steps"), "cut_backs": s.get("cut_backs"),
         "newton": s.get("newton_iterations"), "wall": s.get("wall_time"), "dofs": s.get("dofs"),
         "dz": V * time[-1]}
    m["mean50"] = mean_force(time, F, 0, 50)
    m["mean20"] = mean_force(time, F, 0, 20)
    m["H"], m["folds"] = fold_half_length(p)
    if "P_temperature" in p:
        T = p["P_temperature"]
        k = max(range(len(T)), key=lambda j: T[j])
        m["Tmax"], m["tTmax"] = T[k], p["time"][k]
    return m


def runs_of(path):
    """(label, output directory) of a study directory's runs, or of one output."""
    if os.path.exists(os.path.join(path, "summary.json")):
        return [(os.path.basename(os.path.normpath(path)), path)]
    out = []
    for key in sorted(os.listdir(os.path.join(path, "runs"))):
        record = os.path.join(path, "runs", key, "record.json")
        if not os.path.exists(record):      # a run still going (or killed)
            continue
        rec = json.load(open(record))
        entries = dict(rec.get("overrides", []))
        label = ", ".join("%s=%s" % (k.split("/")[-1], entries[k]) for k in LADDER_KEYS if k in entries)
        out.append(("%s: %s" % (os.path.basename(os.path.normpath(path)), label),
                    os.path.join(path, "runs", key, "out")))
    return out


def main():
    print("| run | DoFs | steps (cut-backs) | Newton | wall [s] | mean force 0-50 mm [kN] | 0-20 mm [kN] "
          "| H [mm] (folds at y) | peak T at P [K] (t [ms]) |")
    print("|---|---|---|---|---|---|---|---|---|")
    for path in sys.argv[1:]:
        for label, out in runs_of(path):
            if not os.path.exists(os.path.join(out, "reactions.csv")):
                print("| %s | no output | | | | | | | |" % label)
                continue
            m = measure(out)
            stop = "" if m["dz"] >= 50 - 1e-3 else " (stopped at Dz = %.1f mm: %s)" % (m["dz"], m["status"])
            print("| %s%s | %s | %s (%s) | %s | %.1f | %.3f | %.3f | %s | %s |" % (
                label, stop, m["dofs"], m["steps"], m["cut_backs"], m["newton"], m["wall"] or 0,
                m["mean50"], m["mean20"],
                "%.2f (%s)" % (m["H"], ", ".join("%g" % y for y in m["folds"])) if m["H"] else "-",
                "%.1f (%.3f)" % (m["Tmax"], 1e3 * m["tTmax"]) if "Tmax" in m else "-"))


if __name__ == "__main__":
    main()

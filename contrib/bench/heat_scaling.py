#!/usr/bin/env python3
"""Benchmark (prints, asserts nothing): the heat system's iterative solver
against problem size (issue 15, "Solvers that scale ... The heat system
likewise").

The heat plate of contrib/bench/heat_plate.prm (a boundary-temperature jump,
convection, DIRK order 3 through ARKode) on n x n Q1 cells, to the first
`--end` seconds, with Heat/Linear solver/Type = iterative: ARKode's Newton
systems M + γK solved by GMRES preconditioned by one AMG V-cycle of the last
set-up's matrix. The mass matrix is lumped so that the linear iterations
thermal.csv counts are the Newton systems' alone (a consistent mass adds its
CG iterations to the same counter); M_L + γK has the conditioning of the
consistent one (both are a mass plus γ times the Laplacian).

Per size: DoFs, ARKode steps, linear solves, GMRES iterations per solve, user
CPU seconds per solve (of the whole run: set-up included) and peak memory per
DoF. Iterations are deterministic; CPU seconds scatter with the machine's load.

Usage: heat_scaling.py BUILD_DIR OUT_DIR [--sizes 62,124,248,496] [--end 2]
       [--direct] (also the direct solver, KLU, at every size)
       [--3d] (the cube 40 mm on n^3 cells, default sizes 10,16,24,32; the same
       boundary conditions on the faces of the same names)
"""
import csv
import json
import os
import subprocess
import sys


def run(build, out, n, solver, end, dim):
    name = "heat%s_%d_%s" % ("_3d" if dim == 3 else "", n, solver)
    directory = os.path.join(out, name)
    root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
    cmd = ["/usr/bin/time", "-f", "%U", "-o", directory + ".time", os.path.join(build, "anvil"),
           os.path.join(root, "contrib", "bench", "heat_plate.prm"), "--threads", "1",
           "--set", "Dimension=%d" % dim,
           "--set", "Geometry/Blocks=" + ("plate: 0, 0, 40, 40, %d, %d" % (n, n) if dim == 2 else
                                          "plate: 0, 0, 0, 40, 40, 40, %d, %d, %d" % (n, n, n)),
           "--set", "Heat/Linear solver/Type=" + solver,
           "--set", "Heat/Linear solver/Mass matrix=lumped",
           "--set", "Time/End time=%g" % end,
           "--set", "Output/Directory=" + directory]
    if dim == 3:
        cmd += ["--set", "Output/Probes=p1: 1, 20, 20; p4: 4, 20, 20; p10: 10, 20, 20"]
    env = dict(os.environ, DEAL_II_NUM_THREADS="1")
    with open(directory + ".log", "w") as log:
        status = subprocess.run(cmd, stdout=log, stderr=subprocess.STDOUT, env=env).returncode
    if status != 0:
        return dict(n=n, solver=solver, status="exit %d" % status)
    rows = list(csv.DictReader(open(os.path.join(directory, "thermal.csv"))))
    total = lambda key: sum(int(r[key]) for r in rows)
    s = json.load(open(os.path.join(directory, "summary.json")))
    user = float(open(directory + ".time").read().split()[-1])
    solves = max(1, total("linear_solves"))
    return dict(n=n, solver=solver, status="completed", dofs=(n + 1) ** dim, arkode=total("arkode_steps"),
                solves=solves, iterations=total("linear_iterations") / solves, user=user,
                user_per_solve=user / solves, memory=s["peak_memory_MB"] * 2 ** 20 / (n + 1) ** dim)


def main(args):
    if len(args) < 2:
        print(__doc__)
        return 1
    build, out = args[0], args[1]
    dim = 3 if "--3d" in args else 2
    sizes, end = ([62, 124, 248, 496] if dim == 2 else [10, 16, 24, 32]), 2.
    for i, a in enumerate(args):
        if a == "--sizes":
            sizes = [int(v) for v in args[i + 1].split(",")]
        if a == "--end":
            end = float(args[i + 1])
    solvers = ["iterative"] + (["direct"] if "--direct" in args else [])
    os.makedirs(out, exist_ok=True)
    print("%5s %-9s %9s %7s %7s %10s %11s %9s %8s" % (
        "n", "solver", "DoFs", "ARKode", "solves", "its/solve", "CPU s/solve", "user s", "B/DoF"))
    results = []
    for n in sizes:
        for solver in solvers:
            r = run(build, out, n, solver, end, dim)
            results.append(r)
            if r["status"] != "completed":
                print("%5d %-9s %s" % (n, solver, r["status"]), flush=True)
                continue
            print("%5d %-9s %9d %7d %7d %10.2f %11.4f %9.1f %8.0f" % (
                n, solver, r["dofs"], r["arkode"], r["solves"], r["iterations"], r["user_per_solve"], r["user"],
                r["memory"]), flush=True)
    print("columns: ARKode steps and linear solves (Newton systems M_L + γK) over the run; its/solve GMRES\n"
          "         iterations per solve (one AMG V-cycle each; direct: 1); CPU s/solve user CPU of the whole\n"
          "         run per solve; B/DoF peak memory per temperature unknown")
    json.dump(results, open(os.path.join(out, "results.json"), "w"), indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))

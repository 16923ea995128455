#!/usr/bin/env python3
"""Benchmark (prints, asserts nothing): the mechanics' linear solvers against
problem size (issue 15, "Solvers that scale").

Per case and size, one run of anvil on one core (DEAL_II_NUM_THREADS=1,
--threads 1) with Mechanics/Linear solver/Type = iterative (GMRES + AMG on
the rigid-body modes, tolerance 1e-8) and, up to a size per case, = direct
(KLU): Krylov iterations per linear solve, Newton iterations, the time per
Newton iteration (assembly + linear solve, from summary.json's phases: wall
times of the process, which scatter under load) and the process's user CPU
seconds. The last table fits t = a N^p per solver (time per Newton iteration
against DoFs) and prints where direct and iterative cross.

Cases:
  2d    plastic F-bar block (contrib/bench/elastic_block.prm with the J2 sets of
        contrib/bench.sh), n x n cells, n = 64 .. 256 (512 with --large)
  3d    the same in 3D, n^3 cells, n = 6 .. 30 (40 and 69, 1 M DoFs, with --large)
  strip contact: contrib/bench/contact_strip.prm, n cells along the upper strip

Usage: solver_scaling.py BUILD_DIR OUT_DIR [--small] [--large] [--cases 2d,3d,strip]
       [--solvers iterative,direct] [--sizes '2d:64,128;3d:10'] [--np 2] [--partition 'per body']
       [--package ML|MueLu] [--preconditioner AMG|geometric] [--refined [--refinements K]] [--tag NAME]
       [--set ENTRY=VALUE ...]

--partition sets Geometry/Partition (default: the scene's, p4est's space-filling
curve); 'per body' cuts every body in np slabs, so that the strip's contact
surface is shared by the processes instead of being their boundary (issue 15).
Its runs are named ..._perbody. "user s" is the CPU seconds of all processes,
"user/rank" per process.

The environment reaches every run: ANVIL_ML_PARAMETERS sets ML's parameters
(e.g. 'smoother: type (level 0)=IFPACK; ...') and ANVIL_ISOCHORIC_MODES=1 adds
the isochoric linear fields to the near-null space, ANVIL_FINE_SMOOTHER=blocks
smooths the fine level with anvil's aggregate-block Gauss-Seidel
(ANVIL_BLOCK_SWEEPS sweeps per smoothing, default 2; doc/linear_solver.md),
ANVIL_ISOCHORIC_MODES=1 with ANVIL_ML_PARAMETERS='smoother: sweeps:int=5' is
session 14's AMG for plastic flow (3D <= 30 Krylov iterations per solve),
ANVIL_COARSE_AGGREGATION=coupled aggregates ML's levels 1 and coarser across
the processes (MIS; doc/performance.md, session 13). OMPI_MCA_mpi_yield_when_idle=1
keeps a waiting rank from spinning when the machine is shared.

--package chooses Mechanics/Linear solver/AMG package (default the scene's, ML);
its runs are named ..._muelu. --tag NAME appends _NAME to the run names (variants
of the same size side by side). ANVIL_MUELU_PARAMETERS sets MueLu's parameters
as ANVIL_ML_PARAMETERS sets ML's (e.g. 'smoother: params/chebyshev: degree:int=5;
sa: use filtered matrix:bool=true'; doc/linear_solver.md, session 16).

Since session 17 the AMG settings are 'automatic': once the material flows plastically,
the isochoric modes with Chebyshev 6 over [lambda_max/100, lambda_max]; --set
'Mechanics/Linear solver/AMG isochoric modes=false' gives the earlier default.

--preconditioner geometric sets Mechanics/Linear solver/Preconditioner (the two-level
preconditioner on the geometric coarse space: doc/linear_solver.md, sessions 20
and 21); its runs are named ..._geometric. --refined meshes the 2d/3d blocks as
n/2 subdivisions refined once (Geometry/Global refinements = 1: the same fine
mesh, p4est's partition of the coarse cells, the coarse space from the mesh
hierarchy); its runs are named ..._refined. --refinements K (with --refined) meshes
n/2^K subdivisions refined K times (the hierarchy path's deeper levels, session 22);
runs named ..._refinedK. ANVIL_GMG_LEVELS=n forces n geometric levels (default: the
automatic rule, doc/linear_solver.md session 22); use --tag to tell such runs apart.

--set passes an entry to every run (e.g. 'Mechanics/Linear solver/AMG rebuild
growth=0' for the hierarchy built at every solve, as before session 8).
"""
import json
import math
import os
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
J2 = ["Mechanics/Element=F-bar", "Bodies/body/Material/Model=J2",
      "Bodies/body/Material/Hardening/Initial yield stress=300",
      "Bodies/body/Material/Hardening/Hardening modulus=1000"]
# Direct solves above these sizes take minutes each (3D: fill-in; at 20^3
# cells, 27 783 DoFs, KLU had not finished its first factorization in 4 min).
DIRECT_LIMIT = {"2d": 256, "3d": 12, "strip": 100000}


REFINED = 0  # --refined [--refinements k]: the 2d/3d blocks as n/2^k subdivisions refined k times (the same fine mesh)


def case_sets(case, n):
    if REFINED and case in ("2d", "3d"):
        if n % (1 << REFINED):
            sys.exit("--refined needs sizes divisible by 2^k")
        scene, sets = case_sets_unrefined(case, n >> REFINED)
        return scene, sets + ["Geometry/Global refinements=%d" % REFINED]
    return case_sets_unrefined(case, n)


def case_sets_unrefined(case, n):
    if case == "2d":
        return "contrib/bench/elastic_block.prm", ["Dimension=2", "Geometry/Blocks=body: 0, 0, 1, 1, %d, %d" % (n, n)] + J2
    if case == "3d":
        return "contrib/bench/elastic_block.prm", [
            "Dimension=3", "Geometry/Blocks=body: 0, 0, 0, 1, 1, 1, %d, %d, %d" % (n, n, n),
            "Boundary conditions/Displacement=front: ux = 0, uy = 0, uz = 0; back: uz = -0.05*t"] + J2
    length = n / 100  # square cells of 0.01 mm, as contrib/bench.sh
    return "contrib/bench/contact_strip.prm", [
        "Geometry/Blocks=lower: 0, 0, %g, 0.02, %d, 2; upper: 0, 0.02, %g, 0.04, %d, 2" % (length, n - 1, length, n),
        "Boundary conditions/Displacement=lower.bottom: ux = 0, uy = 0; upper.left: ux = 0",
        "Mechanics/Linear solver/Tolerance=1e-8"]


def run(build, out, case, n, solver, np, extra=(), partition="", package="", tag=""):
    scene, sets = case_sets(case, n)
    name = "%s_%d_%s_np%d" % (case, n, solver, np) + ("_" + partition.replace(" ", "") if partition else "")
    if package and solver != "direct":
        name += "_" + package.lower()
        sets = sets + ["Mechanics/Linear solver/AMG package=" + package]
    if tag:
        name += "_" + tag
    directory = os.path.join(out, name)
    sets = sets + list(extra) + ["Mechanics/Linear solver/Type=" + solver, "Output/Directory=" + directory]
    if partition:
        sets.append("Geometry/Partition=" + partition)
    cmd = ["/usr/bin/time", "-f", "%U", "-o", directory + ".time"]
    if np > 1:
        cmd += ["mpirun", "--oversubscribe", "-np", str(np)]
    cmd += [os.path.join(build, "anvil"), os.path.join(ROOT, scene), "--threads", "1"]
    for s in sets:
        cmd += ["--set", s]
    env = dict(os.environ, DEAL_II_NUM_THREADS="1", OMPI_ALLOW_RUN_AS_ROOT="1",
               OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    with open(directory + ".log", "w") as log:
        subprocess.run(cmd, stdout=log, stderr=subprocess.STDOUT, env=env)
    try:
        s = json.load(open(os.path.join(directory, "summary.json")))
        user = float(open(directory + ".time").read().split()[-1])
    except (OSError, ValueError):
        return None
    w = s["wall_time_per_phase"]
    newton = max(1, s["newton_iterations"])
    r = dict(case=case, n=n, solver=solver, np=np, partition=partition or "default", package=package or "ML",
             tag=tag, dofs=s["dofs"], status=s["status"], newton=s["newton_iterations"],
             krylov=s["linear_iterations"] / newton, user=user, memory=s["memory_per_dof_bytes"],
             per_newton=(w.get("Mechanics: assembly", 0) + w.get("Mechanics: linear solve", 0)) / newton,
             solve=w.get("Mechanics: linear solve", 0) / newton, assembly=w.get("Mechanics: assembly", 0) / newton)
    print("%-5s %5d %-9s %3d %9d %9s %7d %9.1f %10.3f %10.3f %10.3f %9.1f %9.1f %8.0f" % (
        case, n, solver, np, r["dofs"], r["status"][:9], r["newton"], r["krylov"], r["assembly"], r["solve"],
        r["per_newton"], r["user"], r["user"] / np, r["memory"]), flush=True)
    return r


def fit(rows, key="per_newton"):
    """Least-squares t = a N^p on log-log."""
    if len(rows) < 2:
        return None
    x = [math.log(r["dofs"]) for r in rows]
    y = [math.log(r[key]) for r in rows]
    mx, my = sum(x) / len(x), sum(y) / len(y)
    p = sum((a - mx) * (b - my) for a, b in zip(x, y)) / sum((a - mx) ** 2 for a in x)
    return p, math.exp(my - p * mx)


def main():
    args = sys.argv[1:]
    if len(args) < 2:
        sys.exit(__doc__)
    build, out = args[0], args[1]
    os.makedirs(out, exist_ok=True)
    small, large = "--small" in args, "--large" in args
    cases = ["2d", "3d", "strip"]
    solvers = ["iterative", "direct"]
    np = 1
    partition = ""
    package = tag = ""
    preconditioner = "AMG"
    extra = [args[i + 1] for i, a in enumerate(args) if a == "--set"]
    for i, a in enumerate(args):
        if a == "--cases":
            cases = args[i + 1].split(",")
        if a == "--solvers":
            solvers = args[i + 1].split(",")
        if a == "--np":
            np = int(args[i + 1])
        if a == "--partition":
            partition = args[i + 1]
        if a == "--package":
            package = args[i + 1]
        if a == "--tag":
            tag = args[i + 1]
        if a == "--preconditioner":
            preconditioner = args[i + 1]
    global REFINED
    REFINED = 1 if "--refined" in args else 0
    if REFINED and "--refinements" in args:
        REFINED = int(args[args.index("--refinements") + 1])
    if REFINED:
        tag = "_".join(t for t in (tag, "refined" + (str(REFINED) if REFINED > 1 else "")) if t)
    # Always explicit: since session 22 the entry's default (automatic) picks
    # geometric on the 3D blocks, and "AMG" runs must stay AMG.
    extra.append("Mechanics/Linear solver/Preconditioner=" + preconditioner)
    if preconditioner != "AMG":
        tag = "_".join(t for t in (preconditioner, tag) if t)
    sizes = {"2d": [64, 128, 256] + ([512] if large else []), "3d": [6, 8, 10, 12, 20, 30] + ([40, 69] if large else []),
             "strip": [1000, 4000, 16000]}
    if small:
        sizes = {"2d": [32, 64], "3d": [6, 10], "strip": [500, 1000]}
    for i, a in enumerate(args):
        if a == "--sizes":  # e.g. 2d:64,128;3d:10
            for item in args[i + 1].split(";"):
                case, ns = item.split(":")
                sizes[case] = [int(n) for n in ns.split(",")]
    print("%-5s %5s %-9s %3s %9s %9s %7s %9s %10s %10s %10s %9s %9s %8s" % (
        "case", "n", "solver", "np", "DoFs", "status", "Newton", "Krylov/sv", "asm s/it", "solve s/it",
        "s/Newton", "user s", "user/rank", "B/DoF"))
    results = []
    for case in cases:
        for n in sizes[case]:
            for solver in solvers:
                if solver == "direct" and n > DIRECT_LIMIT[case]:
                    continue
                r = run(build, out, case, n, solver, np, extra, partition, package, tag)
                if r:
                    results.append(r)
    # Appended (one run may add sizes to another's): the input of scaling_figure.py.
    store = os.path.join(out, "results.json")
    kept = json.load(open(store)) if os.path.exists(store) else []
    json.dump(kept + results, open(store, "w"), indent=1)
    print("columns: Krylov/sv GMRES iterations per linear solve (direct: 1); asm, solve s/it: wall seconds per")
    print("         Newton iteration of 'Mechanics: assembly' and 'Mechanics: linear solve'; s/Newton their sum;")
    print("         user s: CPU seconds of the whole process; B/DoF: peak memory per DoF")
    for case in cases:
        fits = {}
        for solver in solvers:
            rows = [r for r in results if r["case"] == case and r["solver"] == solver and r["status"] == "completed"]
            f = fit(rows)
            if f:
                fits[solver] = f
                for r in rows:
                    r["user_per_newton"] = r["user"] / max(1, r["newton"])
                print("%-5s %-9s time per Newton iteration ~ N^%.2f (wall of assembly + solve), "
                      "~ N^%.2f (user CPU of the run per Newton iteration) over %d .. %d DoFs" % (
                          case, solver, f[0], fit(rows, "user_per_newton")[0], rows[0]["dofs"], rows[-1]["dofs"]))
        # Where the measured times per Newton iteration change sign (direct
        # minus iterative), interpolated in log N; else who wins throughout.
        both = {}
        for r in results:
            if r["case"] == case and r["status"] == "completed":
                both.setdefault(r["dofs"], {})[r["solver"]] = r["per_newton"]
        pairs = sorted((n, t["direct"] - t["iterative"]) for n, t in both.items() if len(t) == 2)
        cross = [(a, b) for a, b in zip(pairs, pairs[1:]) if (a[1] > 0) != (b[1] > 0)]
        for (n0, d0), (n1, d1) in cross:
            n = math.exp(math.log(n0) + (math.log(n1) - math.log(n0)) * d0 / (d0 - d1))
            print("%-5s direct and iterative cost the same at about %.0f DoFs (between %d and %d)" % (case, n, n0, n1))
        if pairs and not cross:
            print("%-5s %s is cheaper per Newton iteration at every size measured (%d .. %d DoFs)"
                  % (case, "direct" if pairs[0][1] < 0 else "iterative", pairs[0][0], pairs[-1][0]))


if __name__ == "__main__":
    main()

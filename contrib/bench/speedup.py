#!/usr/bin/env python3
"""Benchmark (prints, asserts nothing): np = 1 against np = 2 on the large
cases of contrib/bench/solver_scaling.py (issue 15: "np = 1 vs 2 speed-up on
the large cases (>= 1.7)").

Usage: speedup.py RESULTS.json [RESULTS.json ...]

Reads the rows solver_scaling.py appended to its results.json (one file may
hold both process counts, or give one file per count) and pairs every run at
np = 2 with the np = 1 run of the same case, size, solver, package and tag
(the np = 1 partition is "default" whatever the np = 2 one). Per pair: the
wall time per Newton iteration of assembly + linear solve (summary.json's
phases) and its speed-up, the same for the assembly and the solve apart, the
Krylov iterations per solve at each count, the ratio of np = 1's CPU seconds
to each rank's (user s / np: the whole run, start-up and output included) and
the solve's speed-up Krylov-corrected: what the solve
would gain had np = 2 kept np = 1's iterations (the part of the loss owed to
the hierarchy rather than to the arithmetic). Wall figures mean something
only on an idle machine: the script prints the load average beside them.
"""
import json
import os
import sys


def key(r):
    return (r["case"], r["n"], r["solver"], r.get("package", "ML"), r.get("tag", ""))


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    rows = []
    for path in sys.argv[1:]:
        rows += json.load(open(path))
    # The last run of each configuration counts (results.json is appended).
    one, two = {}, {}
    for r in rows:
        if r["status"] != "completed":
            continue
        if r["np"] == 1:
            one[key(r)] = r
        elif r["np"] == 2:
            two[(key(r), r.get("partition", "default"))] = r
    pairs = [(one[k], r) for (k, _), r in sorted(two.items()) if k in one]
    if not pairs:
        print("speedup.py: no case was run at both np = 1 and np = 2")
        return
    print("np = 1 against np = 2 (load average %.1f now; wall figures need an idle machine)" % os.getloadavg()[0])
    print("%-5s %6s %-9s %-9s %9s %8s %8s %8s %8s %8s %9s %9s %8s" % (
        "case", "n", "solver", "partition", "DoFs", "s/N np1", "s/N np2", "speed-up", "asm x", "solve x",
        "Krylov", "solve x*", "CPU x"))
    for a, b in pairs:
        ratio = lambda f: a[f] / b[f] if b[f] > 0 else float("nan")
        krylov = "%.1f/%.1f" % (a["krylov"], b["krylov"])
        # Solve time scales with the Krylov count at fixed cost per iteration.
        corrected = ratio("solve") * (b["krylov"] / a["krylov"] if a["krylov"] > 0 else 1)
        print("%-5s %6d %-9s %-9s %9d %8.3f %8.3f %8.2f %8.2f %8.2f %9s %9.2f %8.2f" % (
            a["case"], a["n"], a["solver"], b.get("partition", "default")[:9], a["dofs"], a["per_newton"],
            b["per_newton"], ratio("per_newton"), ratio("assembly"), ratio("solve"), krylov, corrected,
            a["user"] / (b["user"] / b["np"])))
    print("columns: s/N wall seconds of assembly + linear solve per Newton iteration; speed-up their ratio")
    print("         (target >= 1.7); asm x, solve x the two apart; Krylov GMRES iterations per solve np 1 / np 2;")
    print("         solve x* the solve's speed-up had np 2 kept np 1's Krylov count; CPU x np 1's CPU seconds")
    print("         over each rank's (whole run)")


if __name__ == "__main__":
    main()

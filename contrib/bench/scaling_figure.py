#!/usr/bin/env python3
"""Figure (doc/figures/newton_scaling.png): time per Newton iteration against
DoFs from solver_scaling.py's results.json, one core and two processes, with
the fitted exponent of t = a N^p per case over N >= 10^4 (below, the
process's start-up, ~0.3 CPU s, is a large part of a run).

The time per Newton iteration is the user CPU of the whole run over its
Newton iterations (CPU seconds: the wall times scatter on a shared machine);
for np = 2 the wall time of assembly + solve per iteration is drawn as well.

Usage: scaling_figure.py OUT.png RESULTS.json [RESULTS.json ...]
"""
import json
import math
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

LABEL = {"2d": "2D plastic F-bar square", "3d": "3D plastic F-bar cube", "strip": "2D contact strip (elastic)"}
COLOUR = {"2d": "tab:blue", "3d": "tab:red", "strip": "tab:green"}


def fit(x, y):
    lx, ly = [math.log(v) for v in x], [math.log(v) for v in y]
    mx, my = sum(lx) / len(lx), sum(ly) / len(ly)
    p = sum((a - mx) * (b - my) for a, b in zip(lx, ly)) / sum((a - mx) ** 2 for a in lx)
    return p, math.exp(my - p * mx)


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    rows = []
    for f in sys.argv[2:]:
        rows += json.load(open(f))
    rows = [r for r in rows if r["status"] == "completed" and r["solver"] == "iterative"]
    fig, ax = plt.subplots(figsize=(7, 5))
    for case in ("2d", "3d", "strip"):
        one = sorted((r["dofs"], r["user"] / max(1, r["newton"])) for r in rows if r["case"] == case and r["np"] == 1)
        big = [(n, t) for n, t in one if n >= 1e4]
        if len(big) >= 2:
            p, a = fit([n for n, _ in big], [t for _, t in big])
            ax.loglog([n for n, _ in one], [t for _, t in one], "o-", color=COLOUR[case],
                      label="%s, 1 process: t ~ N^%.2f (N >= 1e4)" % (LABEL[case], p))
        two = sorted((r["dofs"], r["per_newton"]) for r in rows if r["case"] == case and r["np"] == 2)
        if two:
            ax.loglog([n for n, _ in two], [t for _, t in two], "s", color=COLOUR[case], mfc="none", ms=9,
                      label="%s, 2 processes (wall, assembly + solve)" % LABEL[case])
    ax.set_xlabel("DoFs")
    ax.set_ylabel("CPU seconds per Newton iteration (whole run)")
    ax.set_title("Time per Newton iteration against size (GMRES + multigrid: 3D geometric, 2D AMG; 1e-8)", fontsize=10)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(sys.argv[1], dpi=110)


if __name__ == "__main__":
    main()

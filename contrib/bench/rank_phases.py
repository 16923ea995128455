#!/usr/bin/env python3
"""Benchmark (prints, asserts nothing): instructions per rank per phase from
callgrind files, one column per file (issue 15, "np = 2 >= 1.7 on the large
cases": where np 2 loses against np 1, counted instead of timed).

Usage: rank_phases.py CALLGRIND_FILE [CALLGRIND_FILE ...]

Make the files with one callgrind output per rank, e.g. the 3D plastic block
of contrib/bench/solver_scaling.py at 16^3, one step, per body:

  OMPI_MCA_mpi_yield_when_idle=1 mpirun --oversubscribe -np 2 \\
    valgrind --tool=callgrind --callgrind-out-file=OUT/cg.%p build/anvil \\
    contrib/bench/elastic_block.prm --threads 1 --set Dimension=3 \\
    --set 'Geometry/Blocks=body: 0, 0, 0, 1, 1, 1, 16, 16, 16' \\
    --set 'Boundary conditions/Displacement=front: ux = 0, uy = 0, uz = 0; back: uz = -0.05*t' \\
    --set Mechanics/Element=F-bar --set Bodies/body/Material/Model=J2 \\
    --set 'Bodies/body/Material/Hardening/Initial yield stress=300' \\
    --set 'Bodies/body/Material/Hardening/Hardening modulus=1000' \\
    --set 'Mechanics/Linear solver/Preconditioner=geometric' \\
    --set 'Time/End time=0.5' --set 'Geometry/Partition=per body'

Rows: inclusive instructions (G) of each phase's function (the largest
entry callgrind_annotate gives for it: inlined copies in other files are
smaller); "assemble" holds assembly and residual (one function). Below the
table: the coarsest level's ML V-cycle per call (ML_Cycle_MG's instructions
over its calls from ML's ApplyInverse) and its parts, so that a cycle's cost
at np 2 can be set against np 1's (ANVIL_GMG_COARSE_CYCLES=k prices k).
MPI polling (opal_progress) is counted where a rank waits: under load it
grows with the wait, so compare it apart.
"""
import re
import subprocess
import sys

PHASES = [
    ("total", "PROGRAM TOTALS"),
    ("assemble (assembly + residual)", "MechanicalProblem<3>::assemble(bool, double) ["),
    ("  cell kernels (worker)", "MechanicalProblem<3>::assemble(bool, double)::{lambda(dealii::TriaActiveIterator"),
    ("  CellScatter::add", "CellScatter<3>::add("),
    ("  OffProcessRows::add", "OffProcessRows<3>::add("),
    ("  OffProcessRows::exchange", "OffProcessRows<3>::exchange("),
    ("setup_matrix", "MechanicalProblem<3>::setup_matrix("),
    ("solve_two_level (linear solve)", "solve_two_level<3>"),
    ("  cycle set-up", "MultilevelPreconditioner::MultilevelPreconditioner("),
    ("    Galerkin products", "anvil::galerkin_product"),
    ("    ML set-up (coarsest)", "anvil::build_amg("),
    ("      its KLU factorisation", "Amesos_Klu::NumericFactorization()"),
    ("  GMRES", "run_gmres<"),
    ("    V-cycles", "MultilevelPreconditioner::vmult("),
    ("      Chebyshev (fine, middle)", "Ifpack_Chebyshev::ApplyInverse("),
    ("      coarsest ML", "???:ML_Cycle_MG ["),
    ("    K products (GMRES)", "dealii::TrilinosWrappers::SparseMatrix::vmult<"),
    ("Epetra imports (ghost exchange)", "Epetra_DistObject::Import(Epetra_SrcDistObject const&, Epetra_Import const&"),
    ("MPI polling (opal_progress)", ":opal_progress ["),
]


def number(line):
    m = re.match(r"\s*([\d,]+)", line)
    return int(m.group(1).replace(",", "")) if m else 0


def inclusive(path):
    out = subprocess.run(["callgrind_annotate", "--inclusive=yes", "--threshold=100", path],
                         capture_output=True, text=True, check=True).stdout.splitlines()
    return {label: max([number(l) for l in out if pattern in l] or [0]) for label, pattern in PHASES}


def ml_cycle(path):
    """ML_Cycle_MG's callees with their call counts (callgrind_annotate --tree=calling)."""
    out = subprocess.run(["callgrind_annotate", "--inclusive=yes", "--tree=calling", "--threshold=100", path],
                         capture_output=True, text=True, check=True).stdout.splitlines()
    parts, inside = {}, False
    for l in out:
        if "*  ???:ML_Cycle_MG [" in l:
            inside, parts["cycle"] = True, (number(l), 0)
        elif inside and not l.strip():
            break
        elif inside:
            m = re.search(r">\s+\S*?:?([\w']+) \(([\d,]+)x\)", l)
            if m:
                parts[m.group(1)] = (number(l), int(m.group(2).replace(",", "")))
    return parts


def main():
    files = sys.argv[1:]
    if not files:
        sys.exit(__doc__)
    columns = [inclusive(f) for f in files]
    print("%-34s" % "G instructions, inclusive" + "".join("%14s" % f[-13:] for f in files))
    for label, _ in PHASES:
        print("%-34s" % label + "".join("%14.3f" % (c[label] / 1e9) for c in columns))
    print("coarsest ML V-cycle per call (M instructions): cycle = smoother (pre + post) + coarser levels + rest")
    for f in files:
        p = ml_cycle(f)
        smoother = p.get("ML_Smoother_Apply", (0, 0))
        calls = smoother[1] // 2 if smoother[1] else 0
        if not calls:
            print("  %s: no ML cycle" % f)
            continue
        coarser = p.get("ML_Cycle_MG'2", (0, 0))[0]
        print("  %s: %d calls, %.2f per cycle (smoother %.2f, coarser levels %.2f)" % (
            f, calls, p["cycle"][0] / calls / 1e6, smoother[0] / calls / 1e6, coarser / calls / 1e6))


if __name__ == "__main__":
    main()

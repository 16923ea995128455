#!/usr/bin/env python3
"""Benchmark helper (prints, asserts nothing): heap bytes at the peak per owner.

Usage: heaptrack_print -f F.zst --flamegraph-cost-type peak -F stacks.txt
       heap_owners.py stacks.txt N_DOFS [--show-other]
Each stack goes to the first owner whose keys it contains (doc/memory.md).
"""
import sys, collections
rules = [
 ("checkpoint: deal.II's packed blocks (cells' pieces + process buffer)", ["pack_data", "save_attached_data"]),
 ("ML: Galerkin products (ML_rap: A·P and Pᵀ(AP))", ["ML_rap"]),
 ("ML: prolongator, aggregates, other", ["ML_", "MultiLevelPreconditioner", "Amesos", "Ifpack"]),
 ("near-null space (rigid-body modes)", ["rigid_body_modes", "as_multivector"]),
 ("Krylov (GMRES basis)", ["SolverGMRES", "GrowingVectorMemory"]),
 ("geometric: Galerkin products (K·P transient, A_c; by rows: A_1 kept, its transients)", ["galerkin_product"]),
 ("geometric: middle levels' Chebyshev, cycle vectors", ["MultilevelPreconditioner", "TwoLevelPreconditioner"]),
 ("geometric: spaces (P, P₂, …, injection, coarse modes)", ["make_coarse_space", "add_coarse_levels", "coarsen_", "inject"]),
 ("J2 point states (one block)", ["contiguous_points", "create_points"]),
 ("step-start table (F_n, F̄_n, u_n key)", ["PointStart", "StepStart"]),
 ("per-point doubles (heat sources, T, Ẇ)", ["PointData<>::reinit", "PointData<>::operator="]),
 ("point table (shared_ptr per point)", ["setup_quadrature_point_data"]),
 ("copier's matrix slots (≤ 64 MB)", ["matrix_slots", "matrix_positions"]),
 ("copier's other tables", ["CellScatter", "AssemblyMapping", "reserve_vector_indices"]),
 ("cells' pattern rows (kept)", ["setup_matrix()::{lambda()#1}"]),
 ("matrix values", ["SparseMatrix::reinit(Epetra_CrsMatrix"]),
 ("matrix values, a second copy (the Copy matrix on the graph, until session 23)", ["Epetra_CrsMatrix::Allocate"]),
 ("matrix graph (column indices)", ["make_serial_matrix", "setup_matrix"]),
 ("output buffers (fields)", ["Fields<>"]),
 ("vectors (Epetra)", ["Vector::reinit", "MPI::Vector"]),
 ("mesh, DoFHandler, p4est", ["Triangulation", "p4est", "DoFHandler", "distribute_dofs", "sc_", "GridGenerator", "create_coarse"]),
 ("MPI, libraries", ["MPI_Init", "_dl_init", "dl-init"]),
]
tot = collections.Counter(); alls = 0
for line in open(sys.argv[1]):
    stack, _, c = line.rstrip().rpartition(" ")
    c = int(c); alls += c
    for name, keys in rules:
        if any(k in stack for k in keys):
            tot[name] += c; break
    else:
        tot["other"] += c
        if "--show-other" in sys.argv and c > 200000:
            print("OTHER", c, stack[-500:], file=sys.stderr)
dofs = float(sys.argv[2])
for name, c in sorted(tot.items(), key=lambda x: -x[1]):
    print("| %s | %.1f | %.0f |" % (name, c / 2**20, c / dofs))
print("| total at the peak | %.1f | %.0f |" % (alls / 2**20, alls / dofs))

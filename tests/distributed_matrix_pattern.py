"""The matrix graph on several processes built from each process's own rows
(source/mechanics/sparsity_rows.cc: the owned cells' rows, rows owned elsewhere
sent to their owners, the column map made as Epetra's FillComplete makes it)
against deal.II's route: the same couplings into a DynamicSparsityPattern
(DoFTools::make_sparsity_pattern, AffineConstraints::add_entries_local_to_global),
SparsityTools::distribute_sparsity_pattern, and the matrix from that pattern
by global indices, Epetra making the column map. With ANVIL_PATTERN_CHECK set,
every new pattern is built both ways and compared on every process (rows,
column map GID for GID, each row's local indices); the run stops at the first
difference.

Independent answer: deal.II's route, entry for entry, at every pattern of
- the two blocks (Pattern look-ahead = 0: a new contact pattern at almost
  every step) on 2 processes (p4est's partition and one slab per body and
  process: contact rows owned by the other process) and on 3 processes
  (remote columns of two owners, grouped by Epetra's sort over the owners);
- the contact strip per body on 2 processes (both bodies cut: the contact
  surface shared by the processes).
Checked: one comparison per pattern (summary.json's pattern_rebuilds), every
one equal, and patterns of different sizes.
"""
import os

from anvil_test import run, check, finish, pattern_checks

os.environ["ANVIL_PATTERN_CHECK"] = "1"
STRIP = ["Geometry/Blocks=lower: 0, 0, 2, 0.02, 199, 2; upper: 0, 0.02, 2, 0.04, 200, 2",
         "Boundary conditions/Displacement=lower.bottom: ux = 0, uy = 0; upper.left: ux = 0",
         "Geometry/Partition=per body", "Time/Time step=0.25"]
CASES = [("prm/two_blocks.prm", ["Contact/Pattern look-ahead=0"], 2, "two_blocks_np2"),
         ("prm/two_blocks.prm", ["Contact/Pattern look-ahead=0", "Geometry/Partition=per body"], 2,
          "two_blocks_per_body_np2"),
         ("prm/two_blocks.prm", ["Contact/Pattern look-ahead=0"], 3, "two_blocks_np3"),
         ("contrib/bench/contact_strip.prm", STRIP, 2, "strip_per_body_np2")]
for scene, sets, np, name in CASES:
    out, summary, stdout = run(scene, sets + ["Output/Field interval=0"], np=np, name="distributed_matrix_" + name)
    compared = pattern_checks(name, summary, stdout)
    if "two_blocks" in name:
        check(len({e for _, e in compared}) > 1, name + ": the contact couplings change the pattern")
finish()

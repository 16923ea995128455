"""The one-process system matrix built straight from the kept cell rows and
the contact couplings (source/mechanics/serial_matrix.cc) against deal.II's
own route: the same couplings into a DynamicSparsityPattern
(DoFTools::make_sparsity_pattern, AffineConstraints::add_entries_local_to_global,
SparsityTools::distribute_sparsity_pattern) and from it the Epetra graph by
global indices. With ANVIL_PATTERN_CHECK set, every new pattern is built
both ways and compared row by row (local indices, column maps); the run stops
at the first difference.

Independent answer: deal.II's route, entry for entry, at every pattern of
- the two blocks with the step's candidates only (Pattern look-ahead = 0:
  a new contact pattern at almost every step of the slide, tests/contact_pattern.py);
- the tube's impact (axisymmetric: axis constraints; the tool and the
  self-contact couplings of the first folds) to 0.3 ms.
Checked: one comparison per pattern (summary.json's pattern_rebuilds, the
set-up's included), every one equal, and patterns of different sizes.
"""
import os

from anvil_test import run, check, finish, pattern_checks

os.environ["ANVIL_PATTERN_CHECK"] = "1"
CASES = [("prm/two_blocks.prm", ["Contact/Pattern look-ahead=0"]),
         ("prm/tube_impact.prm", ["Time/End time=3e-4"])]
for scene, sets in CASES:
    name = os.path.splitext(os.path.basename(scene))[0]
    out, summary, stdout = run(scene, sets + ["Output/Field interval=0"], name="serial_matrix_" + name)
    compared = pattern_checks(name, summary, stdout, min_patterns=2)
    check(len({e for _, e in compared}) > 1, name + ": the contact couplings change the pattern")
finish()

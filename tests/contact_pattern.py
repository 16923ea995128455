"""The contact couplings of the matrix pattern with a look-ahead
(doc/contact.md, "Pattern"; issue 15): the seed's two blocks (prm/two_blocks.prm),
the upper block's 11 bottom nodes sliding 3.75 mm over the lower block's
faces of 0.167 mm in 75 steps of 0.05 mm.

Independent answers:
- the count: with only the step's candidates (Pattern look-ahead = 0) a node
  meets a new face every 0.167 / 0.05 = 3.3 steps, and the 11 nodes (0.125 mm
  apart) do so at different steps, so the pattern grows at almost every step
  of the slide (main: 75 of 79); looking 10 steps (0.5 mm) ahead, a pattern
  lasts until the step's margin (1.5 faces) leaves the look-ahead box
  (0.5 mm + 1.5 faces): ~0.5 / 0.05 = 10 steps, so at most
  1 + 75 / 10 + the pressing's = 10 patterns;
- the answers: the extra couplings are zero entries, so no number in the
  matrix changes; only KLU's pivot order may move round-off: every column of
  contact.csv, newton.csv, energy.csv and the quantities of interest agree
  to 1e-9 of their scale (at least 1e-6 of the file's largest value: the
  balance errors are round-off), and the Newton iterations are equal.
"""
from anvil_test import run, check, finish, largest_column_difference


runs = {}
for look_ahead in (0, 10):
    out, s, _ = run("prm/two_blocks.prm", ["Contact/Pattern look-ahead=%g" % look_ahead],
                    name="contact_pattern_%g" % look_ahead)
    runs[look_ahead] = (out, s)
    print("  look-ahead %2g steps: %3d patterns, %d steps, %d Newton iterations, delta_T %.10f / %.10f K"
          % (look_ahead, s["contact"]["pattern_rebuilds"], s["steps"], s["newton_iterations"],
             s["quantities_of_interest"]["delta_T_upper"], s["quantities_of_interest"]["delta_T_lower"]))

(out0, s0), (out10, s10) = runs[0], runs[10]
check(s0["contact"]["pattern_rebuilds"] >= 50,
      "without look-ahead the pattern grows at almost every step of the slide (%d >= 50)"
      % s0["contact"]["pattern_rebuilds"])
check(s10["contact"]["pattern_rebuilds"] <= 10,
      "looking 10 steps ahead: at most 10 patterns (%d)" % s10["contact"]["pattern_rebuilds"])
check(s0["newton_iterations"] == s10["newton_iterations"] and s0["steps"] == s10["steps"],
      "the same steps and Newton iterations (%d / %d, %d / %d)"
      % (s0["steps"], s10["steps"], s0["newton_iterations"], s10["newton_iterations"]))

worst, where = largest_column_difference(out0, out10, ("contact.csv", "newton.csv", "energy.csv"), s0, s10)
print("  largest difference, relative to its column's scale: %.2e (%s)" % (worst, where))
check(worst < 1e-9, "the answers do not depend on the pattern (%.2e < 1e-9)" % worst)
finish()

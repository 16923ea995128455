"""The matrix pattern of a self-contact pair (doc/contact.md, "Pattern";
issues 12 and 15): the tube's folds (prm/tube_impact.prm, case 3) to
1.2 ms, past the first folds closing onto the skin.

Independent answers:
- the count: with only the step's candidates (Pattern look-ahead = 0) the
  pattern grows whenever a fold's skin comes within the step's search margin
  (1.5 faces) of the skin across it, or the crush shortens the skin's own
  elements enough to bring a face of rings 3-4 within it: once the folds
  form, at most steps (measured: 58 patterns in 83 steps). A fold closes
  over many steps (the crush moves the top by 0.23 mm a step, a face is
  0.5 mm), so a look-ahead of 10 steps along each (node, face)'s own
  relative motion sees a coupling ~10 steps before it is needed: at most a
  quarter as many patterns;
- the answers: the extra couplings are zero entries, so no number in the
  matrix changes; only the LU's pivot order moves round-off: the reaction
  and energy histories and the quantities of interest agree to 1e-8 of their
  scale, with the same steps and Newton iterations.
"""
from anvil_test import run, check, finish, largest_column_difference


runs = {}
for look_ahead in (0, 10):
    out, s, _ = run("prm/tube_impact.prm", ["Contact/Pattern look-ahead=%g" % look_ahead,
                                            "Contact/Self-contact pattern margin=0.5",
                                            "Time/End time=1.2e-3"],
                    name="contact_pattern_self_%g" % look_ahead)
    runs[look_ahead] = (out, s)
    print("  look-ahead %2g steps: %3d patterns, %d steps, %d Newton iterations, crush force %.10g N"
          % (look_ahead, s["contact"]["pattern_rebuilds"], s["steps"], s["newton_iterations"],
             s["quantities_of_interest"]["crush_force"]))

(out0, s0), (out10, s10) = runs[0], runs[10]
check(4 * s10["contact"]["pattern_rebuilds"] <= s0["contact"]["pattern_rebuilds"],
      "looking ahead across the folds: at most a quarter of the patterns (%d vs %d)"
      % (s10["contact"]["pattern_rebuilds"], s0["contact"]["pattern_rebuilds"]))
check(s0["newton_iterations"] == s10["newton_iterations"] and s0["steps"] == s10["steps"],
      "the same steps and Newton iterations (%d / %d, %d / %d)"
      % (s0["steps"], s10["steps"], s0["newton_iterations"], s10["newton_iterations"]))

worst, where = largest_column_difference(out0, out10, ("reactions.csv", "energy.csv"), s0, s10)
print("  largest difference, relative to its column's scale: %.2e (%s)" % (worst, where))
check(worst < 1e-8, "the answers do not depend on the pattern (%.2e < 1e-8)" % worst)
finish()

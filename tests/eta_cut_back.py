"""The progress line's ETA stays honest during a cut-back cascade (issue 16).

The necking bar (prm/necking_bar.prm) with a first step of half the stroke
cuts back in four cascades (Newton failures, inverted elements) before its
step settles. The ETA is (recent cost per simulated second) x (simulated time
left), the cost measured over the last six accepted steps with the failed
attempts between them included (simulator.cc, print_step). With
ANVIL_ETA_CLOCK=iterations its clock counts Newton iterations instead of
seconds (failed attempts included, as they cost wall time), which makes the
check deterministic, free of the machine's load: each line's ETA is held
against the iterations then actually left (the run's total minus the clock
printed on that line).

Honest: the work left never exceeds twice the ETA. Why 2: the ETA cannot
foresee a cascade that has not happened yet; what it can promise is the rate
of the recent steps. A cascade one level deeper than any in its window (the
step halved once more for the rest of the run) doubles the cost per simulated
second, so a line whose future holds no deeper cascade is within a factor 2;
and an ETA that is too high is not dishonest (after a cascade the step grows
again by the growth factor 1.5, so the recent rate over-estimates). The
criterion has teeth: an ETA from the accepted steps' iterations alone,
ignoring the failed attempts (the dishonest variant), is recomputed from the
same lines and must fail it.
"""
import os
import re

from anvil_test import run, check, finish

FACTOR = 2.0
os.environ["ANVIL_ETA_CLOCK"] = "iterations"
out, summary, stdout = run("prm/necking_bar.prm", ["Time/Time step=0.5", "Output/Field interval=0"],
                           name="eta_cut_back")
total = summary["newton_iterations"]
check(summary["cut_backs"] >= 3, "a cascade: %d cut-backs" % summary["cut_backs"])
line = re.compile(r"step +(\d+) +t = (\S+) / (\S+) s.*Newton +(\d+) .*ETA (\S+) s \(clock: (\d+) Newton iterations\)")
rows, failures_before = [], 0
for text in stdout.splitlines():
    if "failed" in text and "cutting back" in text:
        failures_before += 1
    m = line.search(text)
    if m:
        rows.append((int(m.group(1)), float(m.group(2)), float(m.group(3)), int(m.group(4)),
                     float(m.group(5)), int(m.group(6)), failures_before))
check(len(rows) == summary["steps"], "one progress line per accepted step (%d)" % len(rows))
worst = 0.0
for step, t, end, its, eta, clock, failed in rows:
    left = total - clock
    ratio = left / eta if eta > 0 else (0.0 if left == 0 else float("inf"))
    worst = max(worst, ratio)
    print("  step %2d  t = %.4f s  ETA %6.1f  left %4d iterations  left/ETA %.2f  (%d failed attempts so far)"
          % (step, t, eta, left, ratio, failed))
check(worst <= FACTOR, "the work left never exceeds %g x the ETA (worst %.2f)" % (FACTOR, worst))

# The dishonest variant: the same window, the accepted steps' iterations only.
accepted, worst_variant, window = 0, 0.0, []
for step, t, end, its, eta, clock, failed in rows:
    accepted += its
    window.append((accepted, t))
    window = window[-6:]
    first = window[0] if len(window) > 1 else (0, 0.0)
    variant = (accepted - first[0]) / (t - first[1]) * (end - t)
    left = total - clock
    if variant > 0:
        worst_variant = max(worst_variant, left / variant)
check(worst_variant > FACTOR,
      "an ETA ignoring the failed attempts fails the same criterion (worst %.2f > %g)" % (worst_variant, FACTOR))
finish()

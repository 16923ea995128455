"""Time/Breakpoints (issue 13): the time loop lands a step exactly on each
breakpoint and restarts after it from 'Step after breakpoint'; no step
crosses one. Checked on the cantilever (prm/cantilever.prm) with a growing
step (Growth factor 2 up to 0.4 s), breakpoints at 0.33 and 0.7 s and a
restart step of 0.01 s: the accepted times hold 0.33 and 0.7 to round-off,
the step after each is 0.01 s and the next one 0.02 s (growth resumes), and
without breakpoints a step crosses 0.33 (so the first check can fail). Bad
input: breakpoints not increasing give one line naming the entry, exit 2."""
import os
import subprocess

from anvil_test import ANVIL, SOURCE_DIR, run, read_csv, check, close, finish

COMMON = ["Time/Maximum time step=0.4", "Time/Growth factor=2", "Time/Easy step iterations=10",
          "Output/Field interval=0", "Output/Verbosity=quiet"]
out, s, _ = run("prm/cantilever.prm", COMMON + ["Time/Breakpoints=0.33, 0.7",
                                                "Time/Step after breakpoint=0.01"],
                name="time_breakpoints")
times = read_csv(os.path.join(out, "probes.csv"))["time"]
steps = [b - a for a, b in zip(times, times[1:])]
print("  accepted times: " + ", ".join("%.6g" % t for t in times))
for b in (0.33, 0.7):
    hit = [i for i, t in enumerate(times) if abs(t - b) <= 1e-12]
    check(len(hit) == 1, "a step lands on the breakpoint %g s (to 1e-12 s)" % b)
    if hit and hit[0] < len(steps):
        close(steps[hit[0]], 0.01, 1e-12, "the step after the breakpoint %g s (s)" % b)
    check(not any(a < b - 1e-12 and c > b + 1e-12 for a, c in zip(times, times[1:])),
          "no step crosses %g s" % b)

ref, r, _ = run("prm/cantilever.prm", COMMON, name="time_breakpoints_none")
t_ref = read_csv(os.path.join(ref, "probes.csv"))["time"]
check(any(a < 0.33 - 1e-12 and c > 0.33 + 1e-12 for a, c in zip(t_ref, t_ref[1:])),
      "without breakpoints a step crosses 0.33 s (%d steps, %d with them)" % (r["steps"], s["steps"]))
# After the restart step the step grows again by Growth factor (the scene's
# steps are easy: elastic, 1-3 Newton iterations).
i = [k for k, t in enumerate(times) if abs(t - 0.33) <= 1e-12][0]
close(steps[i + 1], 2 * steps[i], 1e-12, "the second step after 0.33 s (s), Growth factor 2")

p = subprocess.run([ANVIL, os.path.join(SOURCE_DIR, "prm", "cantilever.prm"), "--set",
                    "Time/Breakpoints=0.5, 0.2", "--check"], capture_output=True, text=True)
lines = (p.stdout + p.stderr).strip().splitlines()
print("  " + "\n  ".join(lines))
check(p.returncode == 2 and len(lines) == 1 and "Time/Breakpoints" in lines[0]
      and "increasing" in lines[0], "breakpoints 0.5, 0.2: one line naming Time/Breakpoints, exit 2")
finish()

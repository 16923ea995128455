"""Benchmark of the study machinery (prints, asserts nothing about time):

 - overhead: the study's wall time minus the sum of its runs' wall times, with
   one run at a time (reading and checking the study with anvil --check,
   tables, figures), against the sum of the runs;
 - speed-up of independent runs on this machine's cores: the same study with
   1 and 2 runs at once (each run on 1 thread then), wall time ratio.

The study: the Perzyna relaxation (tests/study/orders_backward_euler.prm, 4
runs); --set raises the number of steps so that a run is not only start-up.
"""
import json
import os
import shutil
import subprocess
import time

from anvil_test import ANVIL, SOURCE_DIR, WORK_DIR, check, finish

STUDY = os.path.join(SOURCE_DIR, "tests", "study", "orders_backward_euler.prm")
walls, phases = {}, {}
for jobs in (1, 2):
    out = os.path.join(WORK_DIR, "output", "bench_study_%d" % jobs)
    shutil.rmtree(out, ignore_errors=True)
    start = time.perf_counter()
    p = subprocess.run([ANVIL, "--study", STUDY, "--output", out, "--jobs", str(jobs),
                        "--set", "Time/End time=4"], capture_output=True, text=True)
    walls[jobs] = time.perf_counter() - start
    check(p.returncode == 0, "study with %d run(s) at once exits with 0 %s" % (jobs, p.stderr.strip()))
    with open(os.path.join(out, "timing.json")) as f:
        t = json.load(f)
    phases[jobs] = t["runs_phase_wall"]
    over = walls[jobs] - t["runs_phase_wall"]
    print("%d run(s) at once: study %.2f s = checks before the runs %.2f s (anvil --check per ladder level) + runs "
          "%.2f s (sum of the %d runs' own wall times %.2f s) + the rest %.2f s (start, tables, figures); "
          "overhead over the runs %.2f s" % (jobs, walls[jobs], t["check_wall"], t["runs_phase_wall"], t["executed"],
                                              t["runs_wall_sum"], walls[jobs] - t["check_wall"] - t["runs_phase_wall"],
                                              over))
print("speed-up of 2 concurrent runs on %d core(s): %.2f for the whole study, %.2f for its runs"
      % (os.cpu_count(), walls[1] / walls[2], phases[1] / phases[2]))
finish()

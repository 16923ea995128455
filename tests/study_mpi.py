"""A study gives the same table on 1 and 2 MPI processes per run (--np 2: each
run under mpirun -np 2): the h ladder of tests/study/orders_space.prm, every
value and error to 1e-10 of the value (the heat assembly agrees to round-off
across processes, doc/thermal.md; ARKode's adaptive steps then differ at its
tolerance, 1e-12), the same steps and statuses."""
import csv
import os
import subprocess

from anvil_test import ANVIL, SOURCE_DIR, WORK_DIR, check, finish

STUDY = os.path.join(SOURCE_DIR, "tests", "study", "orders_space.prm")
tables = {}
for np in (1, 2):
    out = os.path.join(WORK_DIR, "output", "study_mpi_%d" % np)
    p = subprocess.run([ANVIL, "--study", STUDY, "--output", out, "--np", str(np), "--jobs", "1"],
                       capture_output=True, text=True)
    check(p.returncode == 0, "study with --np %d exits with 0 %s" % (np, p.stderr.strip()))
    with open(os.path.join(out, "study.csv")) as f:
        tables[np] = list(csv.DictReader(f))
worst = 0.0
for a, b in zip(tables[1], tables[2]):
    for k in ("T_left", "error_T_left"):
        worst = max(worst, abs(float(a[k]) - float(b[k])) / abs(float(a["T_left"])))
    check(a["status"] == b["status"] == "completed" and a["steps"] == b["steps"],
          "h = %s: completed in %s steps on 1 and 2 processes" % (a["h"], a["steps"]))
print("largest difference of T_left and of its error, 1 vs 2 processes, relative to T_left: %.2e" % worst)
check(len(tables[1]) == len(tables[2]) == 4 and worst < 1e-10, "the same table on 1 and 2 processes (%.2e)" % worst)
finish()

"""The study machinery (anvil --study) on tests/study/tool_checks.prm:

 1. a study killed mid-way (its whole process group, runs included) and
    started again reuses the runs it had, runs the others and writes the same
    table as an uninterrupted study (every column but the wall times); a third
    start runs nothing and writes the same file byte for byte; the same runs
    against Reference = finest are reused and give |s(dt) - s(finest)|/|s(finest)|;
 2. a run that cannot complete is a row with status 'failed' and anvil's
    reason, not a failure of the study.
(Physics cost and bad input: tests/study_input.py.)
"""
import csv
import json
import os
import shutil
import signal
import subprocess
import time

from anvil_test import ANVIL, SOURCE_DIR, WORK_DIR, check, finish

STUDY = os.path.join(SOURCE_DIR, "tests", "study", "tool_checks.prm")
BASE = os.path.join(WORK_DIR, "output", "study_tool")
shutil.rmtree(BASE, ignore_errors=True)
os.makedirs(BASE)


def study(path, out, extra=()):
    return subprocess.run([ANVIL, "--study", path, "--output", out] + list(extra), capture_output=True, text=True)


def table(out, drop=("wall_time_median [s]", "wall_time_spread", "peak_memory_MB")):
    with open(os.path.join(out, "study.csv")) as f:
        return [{k: v for k, v in r.items() if k not in drop} for r in csv.DictReader(f)]


# 1. Uninterrupted, then killed after its first finished run and restarted.
full = os.path.join(BASE, "full")
p = study(STUDY, full)
check(p.returncode == 0, "uninterrupted study exits with 0 (%d) %s" % (p.returncode, p.stderr.strip()))
killed = os.path.join(BASE, "killed")
proc = subprocess.Popen([ANVIL, "--study", STUDY, "--output", killed, "--jobs", "1"], stdout=subprocess.DEVNULL,
                        stderr=subprocess.DEVNULL, start_new_session=True)
runs = os.path.join(killed, "runs")
deadline = time.time() + 120
while time.time() < deadline:
    done = [d for d in os.listdir(runs) if os.path.exists(os.path.join(runs, d, "record.json"))] \
        if os.path.isdir(runs) else []
    if done:
        break
    time.sleep(0.1)
os.killpg(proc.pid, signal.SIGKILL)
proc.wait()
n_before = len([d for d in os.listdir(runs) if os.path.exists(os.path.join(runs, d, "record.json"))])
check(0 < n_before < 4 and not os.path.exists(os.path.join(killed, "study.csv")),
      "killed after %d of 4 runs, before writing its table" % n_before)
p = study(STUDY, killed)
with open(os.path.join(killed, "timing.json")) as f:
    timing = json.load(f)
print("  restart: %d run(s) reused, %d executed" % (timing["reused"], timing["executed"]))
check(p.returncode == 0 and timing["reused"] == n_before and timing["executed"] == 4 - n_before,
      "the restart reuses the %d finished run(s) and runs the other %d" % (n_before, 4 - n_before))
check(table(killed) == table(full), "restarted table = uninterrupted table (all columns but wall time and memory)")
with open(os.path.join(killed, "study.csv")) as f:
    first = f.read()
p = study(STUDY, killed)
with open(os.path.join(killed, "study.csv")) as f:
    again = f.read()
with open(os.path.join(killed, "timing.json")) as f:
    timing = json.load(f)
check(timing["executed"] == 0 and again == first, "a third start runs nothing and writes the same file")

# 2. Failed runs: the Newton limit of 1 at the minimum time step.
rows = table(full)
failed = [r for r in rows if r["newton"] == "1"]
ok = [r for r in rows if r["newton"] == "15"]
check(all(r["status"] == "failed" and "Newton did not converge" in r["reason"] for r in failed),
      "runs with 1 Newton iteration: status failed, reason '%s'" % failed[0]["reason"])
check(all(r["status"] == "completed" and r["reason"] == "" for r in ok), "the other runs completed")
with open(os.path.join(full, "study.md")) as f:
    md = f.read()
section = md.split("## Runs that did not complete")[-1]
check(section.count("Newton did not converge") == 2,
      "study.md lists the 2 failed runs with their reason")

# The same runs against the finest of each group (Reference/Type = finest):
# all reused, only the table changes.
finest = os.path.join(BASE, "finest.prm")
with open(STUDY) as f:
    body = f.read().replace("relaxation.prm", os.path.join(SOURCE_DIR, "tests", "study", "relaxation.prm"))
with open(finest, "w") as f:
    f.write(body[:body.index("subsection Reference")] + "subsection Reference\n  set Type = finest\nend\n")
p = study(finest, full)
with open(os.path.join(full, "timing.json")) as f:
    timing = json.load(f)
rows = {(r["dt"], r["newton"]): r for r in table(full)}
coarse, fine = rows["0.1", "15"], rows["0.05", "15"]
expected = abs(float(coarse["s"]) - float(fine["s"])) / abs(float(fine["s"]))
check(p.returncode == 0 and timing["executed"] == 0, "Reference = finest: the runs are reused (%d executed)"
      % timing["executed"])
check(abs(float(coarse["error_s"]) - expected) < 1e-12 and float(fine["error_s"]) == 0,
      "Reference = finest: dt = 0.1 error %s = |s(0.1) - s(0.05)|/|s(0.05)| = %.6g; the finest run's 0"
      % (coarse["error_s"], expected))
check(rows["0.1", "1"]["error_s"] in ("", "nan"), "Reference = finest: no error for a group whose finest run failed")

finish()

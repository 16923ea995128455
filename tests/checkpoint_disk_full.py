"""A checkpoint that cannot be written (issue 17, "faults survived").

The disk fills while a checkpoint is written: with ANVIL_CHECKPOINT_FAULT=full:3
(tests only) the third checkpoint's state file is a link to /dev/full, so the
kernel answers "No space left on device" exactly as a full disk would. The
promises checked, on 1 and 2 processes:
  - the run stops with exit 3 and one line naming the file and the reason,
    on every process at once (no MPI_Abort after a rank waited in a barrier),
    no deal.II banner;
  - the previous good checkpoint (the second, at step 2 N) is kept, whole;
  - summary.json says why it stopped and the histories are closed;
  - a restart from that checkpoint ends with the uninterrupted run's answer
    (the independent reference): same rows, times strictly increasing, values
    to 1e-10 of each column's range on one process (1e-8 on two).
"""
import json
import os
import shutil
import subprocess

from anvil_test import ANVIL, SOURCE_DIR, WORK_DIR, read_csv, check, finish

SCENE = os.path.join(SOURCE_DIR, "prm", "two_blocks.prm")
N = 5  # checkpoint interval
SETS = ["Time/End time=2e-3", "Output/Field interval=0", "Output/Verbosity=quiet",
        "Output/Checkpoint interval=%d" % N]
HISTORIES = ("reactions.csv", "energy.csv", "contact.csv", "thermal.csv")
root = os.path.join(WORK_DIR, "output", "checkpoint_disk_full")
shutil.rmtree(root, ignore_errors=True)


def run(out, np=1, fault=None, restart=False):
    cmd = [ANVIL, SCENE, "--set", "Output/Directory=" + out]
    for s in SETS + (["Output/Restart from=" + out + "/checkpoint"] if restart else []):
        cmd += ["--set", s]
    if np > 1:
        cmd = ["mpirun", "-np", str(np), "--oversubscribe"] + cmd
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
               DEAL_II_NUM_THREADS="1")
    env.pop("ANVIL_CHECKPOINT_FAULT", None)
    if fault:
        env["ANVIL_CHECKPOINT_FAULT"] = fault
    p = subprocess.run(cmd, capture_output=True, text=True, env=env, timeout=600)
    return p.returncode, p.stderr


def state(directory):
    entries = {}
    for line in open(os.path.join(directory, "state.txt")):
        if line.strip() == "contact":
            break
        key, _, value = line.strip().partition(" ")
        entries[key] = value
    return entries


def columns(path):
    return {k.split(" [")[0]: v for k, v in read_csv(path).items()}


def compare(ref, out, rtol, what, np):
    for f in HISTORIES:
        a, b = columns(os.path.join(ref, f)), columns(os.path.join(out, f))
        # Wall times are not answers; Krylov counts depend on the partition.
        for name in list(a):
            if name.endswith("wall_time") or (np > 1 and name == "linear_iterations"):
                del a[name]
        tb = b["time"]
        increasing = all(t1 < t2 for t1, t2 in zip(tb, tb[1:]))
        floor = 1e-10 * max(max(abs(x) for x in v) for k, v in a.items() if k not in ("step", "time"))
        worst = 0.0
        if len(a["time"]) == len(tb):
            for name in a:
                scale = max(max(abs(x) for x in a[name]), floor / rtol, 1e-300)
                worst = max([worst] + [abs(x - y) / scale for x, y in zip(a[name], b[name])])
        check(len(a["time"]) == len(tb) and increasing and worst <= rtol,
              "%s: %s has %d rows (uninterrupted %d), times %s increasing, largest difference "
              "%.1e (limit %.0e)" % (what, f, len(tb), len(a["time"]), "" if increasing else "NOT",
                                     worst, rtol))


ref = os.path.join(root, "reference")
status, err = run(ref)
check(status == 0, "uninterrupted run: exit %d %s" % (status, err.strip()[:300]))

for np in (1, 2):
    out = os.path.join(root, "full_np%d" % np)
    status, err = run(out, np, fault="full:3")
    # mpirun adds its own note that a process ended with a non-zero status.
    lines = [l for l in err.splitlines() if l.startswith("anvil")]
    check(status == 3, "np %d, disk full at the 3rd checkpoint: exit %d (expected 3)" % (np, status))
    check(len(lines) == 1 and "No space left on device" in lines[0] and "state.txt" in lines[0]
          and "previous checkpoint" in lines[0],
          "np %d: one line naming the file and the reason: %r" % (np, err.strip()[:400]))
    check("MPI_ABORT" not in err and "An error occurred" not in err and "Exception" not in err,
          "np %d: every process ends together, no MPI_Abort, no deal.II banner" % np)
    kept = state(out + "/checkpoint")
    check(kept.get("steps") == str(2 * N),
          "np %d: the last good checkpoint (step %d) is kept: it holds step %s"
          % (np, 2 * N, kept.get("steps")))
    summary = json.load(open(os.path.join(out, "summary.json")))
    check(summary["status"].startswith("stopped") and "No space left" in summary["status"],
          "np %d: summary.json says why: %r" % (np, summary["status"][:200]))
    rows = columns(os.path.join(out, "energy.csv"))["step"]
    check(rows and rows[-1] == 3 * N,
          "np %d: the histories hold every accepted step up to the failure (last row step %s)"
          % (np, rows[-1] if rows else None))
    status, err = run(out, np, restart=True)
    check(status == 0, "np %d: restart from the kept checkpoint: exit %d %s"
          % (np, status, err.strip()[:300]))
    compare(ref, out, 1e-10 if np == 1 else 1e-8, "np %d, restarted after a full disk" % np, np)

finish()

"""Faults survived (issue 17): SIGKILL at random moments, restart, same answer.

The two-block scene (contact, friction, frictional heating) and the thermal
necking bar (adiabatic split, heat equation) are run uninterrupted on one
process: the reference. Then, for each pair (processes of the killed run,
processes of the restart) in (1, 1), (1, 2), (2, 1), (2, 2), a run that writes a
checkpoint every step is killed (SIGKILL to the whole process group, mpirun and
its ranks) at a seeded random moment of its expected wall time, restarted from
its last checkpoint (from scratch if it died before the first one), killed once
more in the (2, 1) case, and run to the end. The independent answer is the
uninterrupted run: every history (reactions, energies, probes, contact) has
the same rows, times strictly increasing and none twice, and the same values
(to 1e-8 of each column's largest value on one process, 1e-5 across process
counts, where the heat solver's decisions may differ: issue 17, "one answer";
columns at the round-off level of their file compare against 1e-10 of the
file's largest value);
thermal.csv and newton.csv the same times. A kill during a checkpoint write
is simulated exactly: a half-written checkpoint.new beside the good one, and
the window between write_checkpoint's two renames (only checkpoint.old left):
the restart uses the last good checkpoint and ends with the same answer.
Usage: kill_restart.py [SEED]"""
import os
import random
import shutil
import signal
import subprocess
import sys
import time

from anvil_test import ANVIL, SOURCE_DIR, WORK_DIR, read_csv, check, finish

SEED = int(sys.argv[1]) if len(sys.argv) > 1 else 7
rng = random.Random(SEED)
SCENES = [("two_blocks", "prm/two_blocks.prm", ["Time/End time=2e-3"]),
          ("necking_bar_thermal", "prm/necking_bar_thermal.prm",
           ["Time/Time step=0.25", "Time/End time=2.5"])]
COMMON = ["Output/Field interval=0", "Output/Verbosity=quiet", "Output/Checkpoint interval=1"]
FULL_VALUES = ("reactions.csv", "energy.csv", "probes.csv", "contact.csv")
TIMES_ONLY = ("thermal.csv", "newton.csv")
ENV = dict(os.environ, DEAL_II_NUM_THREADS="1", OMPI_ALLOW_RUN_AS_ROOT="1",
           OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")


def command(scene, sets, out, np, restart):
    cmd = [ANVIL, os.path.join(SOURCE_DIR, scene), "--set", "Output/Directory=" + out]
    extra = ["Output/Restart from=" + out + "/checkpoint"] if restart else []
    for s in sets + COMMON + extra:
        cmd += ["--set", s]
    return (["mpirun", "-np", str(np), "--oversubscribe"] if np > 1 else []) + cmd


def run(cmd, kill_after=None):
    """Run cmd; with kill_after, SIGKILL its process group after that many
    seconds. Returns (exit status or 'killed', stderr)."""
    p = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, env=ENV,
                         start_new_session=True)
    try:
        _, err = p.communicate(timeout=kill_after if kill_after else 900)
        return p.returncode, err.decode(errors="replace")
    except subprocess.TimeoutExpired:
        kill_session(p.pid)
        p.communicate()
        return "killed", ""


def kill_session(sid):
    """SIGKILL every process of session sid, and wait until none is left:
    mpirun puts each rank in a process group of its own (same session), so
    killing mpirun's group left the ranks running on, writing checkpoints into
    the directory the restart was reading (checkpoint.new removed under it)."""
    deadline = time.time() + 10
    while time.time() < deadline:
        alive = []
        for entry in os.listdir("/proc"):
            if entry.isdigit():
                try:
                    if os.getsid(int(entry)) == sid:
                        os.kill(int(entry), signal.SIGKILL)
                        alive.append(entry)
                except (ProcessLookupError, PermissionError):
                    pass
        if not alive:
            return
        time.sleep(0.05)


def columns(path):
    """A CSV as {name before ' [': values} (units in headers may come)."""
    return {k.split(" [")[0]: v for k, v in read_csv(path).items()}


def compare(ref_dir, out_dir, rtol, what):
    for f in FULL_VALUES + TIMES_ONLY:
        a_path, b_path = os.path.join(ref_dir, f), os.path.join(out_dir, f)
        if not os.path.exists(a_path):
            continue
        if not os.path.exists(b_path):
            check(False, "%s: %s is missing" % (what, f))
            continue
        a, b = columns(a_path), columns(b_path)
        ta, tb = a["time"], b["time"]
        strictly = all(t1 < t2 for t1, t2 in zip(tb, tb[1:])) if f != "newton.csv" else \
            all(t1 <= t2 for t1, t2 in zip(tb, tb[1:]))
        same_rows = len(ta) == len(tb)
        worst, where = 0.0, ""
        # A column at the round-off level of its file's quantity (the reaction
        # of a free boundary, a balance error beside the energies it balances)
        # compares against 1e-10 of the file's largest value, as in the
        # regression layer.
        floor = 1e-10 * max(max(abs(x) for x in v) for k, v in a.items() if k not in ("step", "time"))
        if same_rows:
            for name in (a if f in FULL_VALUES else ["time"]):
                if name not in b:
                    check(False, "%s: %s has no column %s" % (what, f, name))
                    continue
                scale = max(max(abs(x) for x in a[name]), floor / rtol, 1e-300)
                for i, (x, y) in enumerate(zip(a[name], b[name])):
                    d = abs(x - y) / scale
                    if d > worst:
                        worst, where = d, "%s row %d (%g vs %g)" % (name, i, x, y)
        check(same_rows and strictly and worst <= rtol,
              "%s: %s has %d rows (uninterrupted %d), times %s, largest difference %.1e of the "
              "column's range (limit %.0e) %s" % (what, f, len(tb), len(ta),
                                                   "increasing" if strictly else "NOT increasing",
                                                   worst, rtol, where))


root = os.path.join(WORK_DIR, "output", "kill_restart")
shutil.rmtree(root, ignore_errors=True)
counts = {"kills": 0, "restarts": 0, "runs from scratch after an early kill": 0,
          "runs that ended before their kill": 0}
for name, scene, sets in SCENES:
    ref = os.path.join(root, name + "_reference")
    start = time.time()
    status, err = run(command(scene, sets, ref, 1, False))
    wall = time.time() - start
    check(status == 0, "%s uninterrupted: exit %s %s" % (name, status, err.strip()[:300]))
    print("%s: uninterrupted run %.1f s" % (name, wall))
    for np_kill, np_restart in [(1, 1), (1, 2), (2, 1), (2, 2)]:
        out = os.path.join(root, "%s_%d_%d" % (name, np_kill, np_restart))
        legs = [np_kill, np_kill, np_restart] if (np_kill, np_restart) == (2, 1) else [np_kill, np_restart]
        for leg, np in enumerate(legs):
            last = leg == len(legs) - 1
            restart = os.path.exists(out + "/checkpoint/state.txt") or \
                os.path.exists(out + "/checkpoint.old/state.txt")
            if leg > 0:
                counts["restarts" if restart else "runs from scratch after an early kill"] += 1
            after = None if last else rng.uniform(0.2, 0.9) * wall * (1.6 if np > 1 else 1.0)
            status, err = run(command(scene, sets, out, np, restart), after)
            if status == "killed":
                counts["kills"] += 1
                print("  %s, np %d: killed after %.1f s" % (os.path.basename(out), np, after))
            elif not last:
                counts["runs that ended before their kill"] += 1
            if last or status != "killed":
                check(status == 0, "%s, np %d: exit %s %s" % (os.path.basename(out), np, status,
                                                              err.strip()[:300]))
                break
        compare(ref, out, 1e-8 if (np_kill, np_restart) == (1, 1) else 1e-5,
                "%s killed on %d, resumed on %d" % (name, np_kill, np_restart))

    # A kill during a checkpoint write: a half-written checkpoint.new beside
    # the last good one, then the window between the two renames.
    half = os.path.join(root, name + "_half")
    halfway = [s for s in sets if not s.startswith("Time/End time")]
    end = float([s for s in sets if s.startswith("Time/End time")][0].split("=")[1])
    status, _ = run(command(scene, halfway + ["Time/End time=%r" % (end / 2)], half, 1, False))
    os.makedirs(half + "/checkpoint.new", exist_ok=True)
    open(half + "/checkpoint.new/state.txt", "w").write("anvil-checkpoint 3\ntime 1")
    with open(half + "/checkpoint.new/mesh", "wb") as f:
        f.write(os.urandom(1000))
    window = half + "_window"
    shutil.copytree(half, window)
    os.rename(window + "/checkpoint", window + "/checkpoint.old")
    for out, what in [(half, "a half-written checkpoint.new"), (window, "only checkpoint.old")]:
        status, err = run(command(scene, sets, out, 1, True))
        counts["restarts"] += 1
        check(status == 0, "%s: restart after a kill during a checkpoint write (%s): exit %s %s"
              % (name, what, status, err.strip()[:300]))
        compare(ref, out, 1e-8, "%s resumed beside %s" % (name, what))

print("faults: " + ", ".join("%s: %d" % kv for kv in counts.items()))
finish()

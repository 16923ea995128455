"""The energy audit's terms kept from the step's last evaluation (issue 15).

Newton's evaluations whose state the convergence test may accept sum the
points' audit terms in the assembly's cell pass (Context::audit), and
commit_step() takes those sums instead of a pass of its own over the cells,
but only where they are the committed state's: no assembly since (the points'
stresses, Ẇirr and temperatures are that evaluation's), the same u to the
bit, the same step (assembly.cc, audit_from_kept). Anything else falls back to
the pass. The pass is the independent answer: the same operations on the same
numbers in the same order, so the sums must be equal to the bit.

With ANVIL_AUDIT_CHECK set every accepted step that takes the kept sums runs
the pass too, stops if one of the seven sums differs by more than 1e-12 of the
largest, and prints the difference; a step that falls back prints "pass".

 a. Every route to a commit: the cantilever (residual-only predictions that
    fail and are assembled again), the necking bar whose first step of half
    the stroke is cut back (reverted attempts), the tube (dynamics, contact,
    line search, adiabatic split), two blocks (contact's active set) on one
    and two processes, the twisted bar (3D: no start-of-step table), the
    thermal necking bar as shipped (adiabatic split), iterated staggered (the step
    solved again from the last solution) and monolithic (the coupled Newton
    evaluates outside the mechanics' own: the pass). Every step compared, the
    kept sums equal to the bit; the mechanics-driven scenes take them at most
    steps, the monolithic one never.
 b. The check can fail: ANVIL_AUDIT_STALE (test only) takes the sums of the
    attempt's last audited evaluation whatever came after it. On the
    monolithic scene (its first iterate from the mechanics alone at T_n, then
    coupled iterates nobody audits) the run stops with the check's message.
 c. energy.csv written from the kept sums equals, byte for byte, the file of
    the same run whose steps all took the pass's numbers (ANVIL_AUDIT_CHECK
    keeps the pass's after comparing).
 d. A restart from a checkpoint gives the uninterrupted run's audit
    (energy.csv rows byte-equal), and two processes the audit of one (the
    cantilever: every energy of the summary to 1e-10 of the largest).
"""
import filecmp
import os
import re
import subprocess

from anvil_test import ANVIL, SOURCE_DIR, WORK_DIR, run, read_csv, check, finish

QUIET = ["Output/Field interval=0", "Output/Verbosity=quiet"]
CASES = [
    ("cantilever", "prm/cantilever.prm", [], 1, True),
    ("cut_back", "prm/necking_bar.prm", ["Time/Time step=0.5", "Time/End time=2"], 1, True),
    ("tube", "prm/tube_impact.prm", ["Time/End time=1e-4"], 1, True),
    ("two_blocks", "prm/two_blocks.prm", ["Time/End time=1e-3"], 1, True),
    ("two_blocks_np2", "prm/two_blocks.prm", ["Time/End time=1e-3"], 2, True),
    ("twisted_bar_3d", "prm/twisted_bar_3d.prm", [], 1, True),
    ("adiabatic", "prm/necking_bar_thermal.prm", ["Time/End time=1"], 1, True),
    ("staggered", "prm/necking_bar_thermal.prm",
     ["Physics/Coupling=iterated staggered", "Time/End time=1"], 1, True),
    ("monolithic", "prm/necking_bar_thermal.prm",
     ["Physics/Coupling=monolithic", "Time/Time step=0.25", "Time/End time=1"], 1, False),
]


def audited(name, scene, sets, np, env_extra=None, expect_status=0):
    os.environ["ANVIL_AUDIT_CHECK"] = "1"
    for k, v in (env_extra or {}).items():
        os.environ[k] = v
    try:
        return run(scene, QUIET + sets, np=np, name="audit_kept_" + name, expect_status=expect_status)
    finally:
        os.environ.pop("ANVIL_AUDIT_CHECK", None)
        for k in env_extra or {}:
            os.environ.pop(k, None)


# a. and c.
for name, scene, sets, np, mostly_kept in CASES:
    out, summary, stdout = audited(name, scene, sets, np)
    lines = re.findall(r"ANVIL_AUDIT_CHECK step audit: (kept, difference (\S+) of (\S+) N mm|pass)", stdout)
    kept = [(float(d), float(s)) for whole, d, s in lines if whole.startswith("kept")]
    passes = len(lines) - len(kept)
    steps = summary.get("steps", 0)
    worst = max((d / s if s else d) for d, s in kept) if kept else 0.0
    print("  %s (np %d): %d steps, %d cut-backs, %d Newton; kept sums at %d steps (largest difference %.1e "
          "relative), the pass at %d" % (name, np, steps, summary.get("cut_backs", 0),
                                         summary.get("newton_iterations", 0), len(kept), worst, passes))
    check(steps > 0 and len(lines) == steps, name + ": every accepted step's audit compared (%d of %d)"
          % (len(lines), steps))
    check(worst == 0.0, name + ": the kept sums equal the pass's to the bit")
    if mostly_kept:
        check(len(kept) >= 0.8 * steps, name + ": the kept sums at most steps (%d of %d)" % (len(kept), steps))
    else:
        check(len(kept) == 0, name + ": evaluated outside the mechanics' Newton: the pass at every step")
    # c. The same run without the check writes the kept sums' numbers.
    plain, _, _ = run(scene, QUIET + sets, np=np, name="audit_kept_plain_" + name)
    check(filecmp.cmp(out + "/energy.csv", plain + "/energy.csv", shallow=False),
          name + ": energy.csv from the kept sums byte-equal to the pass's")
    if name == "cut_back":
        check(summary.get("cut_backs", 0) > 0, name + ": a step was cut back")

# b. Stale sums are caught: the same check fails when the stamp is ignored.
stale = os.path.join(WORK_DIR, "output", "audit_kept_stale")
env = dict(os.environ, ANVIL_AUDIT_CHECK="1", ANVIL_AUDIT_STALE="1", DEAL_II_NUM_THREADS="1")
p = subprocess.run([ANVIL, os.path.join(SOURCE_DIR, "prm/necking_bar_thermal.prm"),
                    "--set", "Output/Directory=" + stale, "--set", "Physics/Coupling=monolithic",
                    "--set", "Time/Time step=0.25", "--set", "Time/End time=0.5"]
                   + sum([["--set", x] for x in QUIET], []), capture_output=True, text=True, env=env)
said = re.search(r"ANVIL_AUDIT_CHECK: the kept audit differs from the pass by \S+", p.stdout + p.stderr)
print("  stale sums (monolithic): exit status %d, %s" % (p.returncode, said.group(0) if said else "no message"))
check(p.returncode != 0 and said is not None, "stale kept sums stop the run with the check's message")

# d. A restart gives the uninterrupted run's audit; two processes the audit of one.
base = QUIET + ["Time/Time step=0.1"]
full, _, _ = run("prm/necking_bar.prm", base, name="audit_kept_full")
half, _, _ = run("prm/necking_bar.prm", base + ["Time/End time=1"], name="audit_kept_half")
resumed, _, _ = run("prm/necking_bar.prm", base + ["Output/Restart from=" + half + "/checkpoint"],
                    name="audit_kept_half")
a, b = open(full + "/energy.csv").read().splitlines(), open(resumed + "/energy.csv").read().splitlines()
check(len(a) == len(b) and a == b, "resumed at t = 1: energy.csv rows byte-equal to the uninterrupted run's "
      "(%d rows)" % len(b))
_, one, _ = run("prm/cantilever.prm", QUIET, name="audit_kept_np1")
_, two, _ = run("prm/cantilever.prm", QUIET, np=2, name="audit_kept_np2")
energies = [k for k, v in one["energy"].items() if isinstance(v, float) and not k.endswith("error")]
scale = max(abs(one["energy"][k]) for k in energies)
worst = max(abs(two["energy"][k] - one["energy"][k]) for k in energies) / scale
print("  cantilever np 2 against np 1: largest difference of the summary's energies %.1e of the largest (%.6g N mm)"
      % (worst, scale))
check(worst <= 1e-10, "np 2 = np 1 (the summary's energies to 1e-10 of the largest)")
finish()

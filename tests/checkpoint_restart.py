"""Nothing computed is lost: checkpoint and restart.

 1. The necking bar run to t = 0.5 and resumed from its checkpoint on two
    processes ends with the answer of the uninterrupted run (quantities of
    interest to 1e-9 relative, the same reaction history, the same plastic
    work).
 2. A run that cannot go on (a plastic-increment limit no step can meet, and
    no room to cut back) exits with status 3, says why, and leaves its last
    converged fields, summary.json (status failed) and a checkpoint; resumed
    from that checkpoint without the limit it completes with the same answer.
 3. A coupled heat scene (adiabatic split, convection, thermal softening and
    expansion) stopped half way and resumed on two processes: the temperature
    field, the points' temperatures and the heat audit come back, so the end
    temperature, force and heat balance equal the uninterrupted run's.
 4. A checkpoint written with a large step (0.25 s, the whole first half)
    resumed by a scene that now says 0.05 s continues with 0.05 s steps (the
    rows of reactions.csv after the restart are 0.05 s apart), and the first
    progress line says so (issue 17: a failed run's step was kept)."""
import os
import re
from anvil_test import run, read_csv, check, close, finish

base = ["Output/Field interval=0", "Output/Verbosity=quiet"]
out_full, full, _ = run("prm/necking_bar.prm", base, name="ckpt_full")
out_half, half, _ = run("prm/necking_bar.prm", base + ["Time/End time=0.5"], name="ckpt_half")
check(os.path.exists(out_half + "/checkpoint/state.txt"), "a checkpoint is written at the end of a run")
_, resumed, _ = run("prm/necking_bar.prm", base + ["Output/Restart from=" + out_half + "/checkpoint"],
                    np=2, name="ckpt_half")
for k, v in full["quantities_of_interest"].items():
    close(resumed["quantities_of_interest"][k], v, 1e-9, "resumed on 2 processes: " + k)
close(resumed["energy"]["plastic_work"], full["energy"]["plastic_work"], 1e-9, "resumed: plastic work")
a, b = read_csv(out_full + "/reactions.csv"), read_csv(out_half + "/reactions.csv")
check(len(a["time"]) == len(b["time"]), "the resumed history continues the first one (%d rows)" % len(b["time"]))
check(max(abs(x - y) for x, y in zip(a["top_Fy"], b["top_Fy"])) < 1e-6 * max(a["top_Fy"]),
      "same reaction history")

out_fail, failed, _ = run("prm/necking_bar.prm", base + ["Mechanics/Maximum plastic strain increment=1e-4",
                                                          "Time/Minimum time step=0.02"],
                          name="ckpt_fail", expect_status=3)
check(failed["status"].startswith("failed"), "summary.json says the run failed: " + failed["status"])
check(os.path.exists(out_fail + "/checkpoint/state.txt"), "the failed run left a checkpoint")
check(os.path.exists(out_fail + "/solution.pvd"), "and its last converged fields")
_, rescued, _ = run("prm/necking_bar.prm", base + ["Output/Restart from=" + out_fail + "/checkpoint"], name="ckpt_fail")
close(rescued["quantities_of_interest"]["final_force"], full["quantities_of_interest"]["final_force"], 1e-9,
      "resumed after the failure: final force")

heat = ["Physics/Coupling=adiabatic split", "Time/Time step=0.1",
        "Bodies/body/Material/Elasticity/Thermal expansion=1.2e-5",
        "Bodies/body/Material/Hardening/Thermal softening/Model=linear",
        "Bodies/body/Material/Hardening/Thermal softening/Softening coefficient=2e-3",
        "Bodies/body/Material/Hardening/Thermal softening/Reference temperature=293",
        "Heat/Boundary conditions/Convection=bottom: 0.5, 293",
        "Output/Probes=corner: 1.1, 1",
        "Output/Quantities of interest=T: mean(temperature); Tmax: max(temperature); "
        "Tc: probe(corner, temperature); F: reaction(bottom, y)"]
out_full, full, _ = run("tests/plastic_block.prm", heat, name="ckpt_heat_full")
out_half, _, _ = run("tests/plastic_block.prm", heat + ["Time/End time=0.5"], name="ckpt_heat_half")
_, resumed, _ = run("tests/plastic_block.prm", heat + ["Output/Restart from=" + out_half + "/checkpoint"],
                    np=2, name="ckpt_heat_half")
for k, v in full["quantities_of_interest"].items():
    close(resumed["quantities_of_interest"][k], v, 1e-8, "heat scene resumed on 2 processes: " + k)
for k in ("heat_content_change", "plastic_heat", "thermoelastic_heat", "boundary_heat_in"):
    close(resumed["heat"][k], full["heat"][k], 1e-7, "heat scene resumed: " + k + " (mJ)")
a, b = read_csv(out_full + "/probes.csv"), read_csv(out_half + "/probes.csv")
check(len(a["time"]) == len(b["time"]) and
      max(abs(x - y) for x, y in zip(a["corner_temperature"], b["corner_temperature"])) < 1e-7,
      "the same temperature history at the probe (%d rows)" % len(b["time"]))
# A checkpoint that does not match the scene is refused before any work, with
# one line naming Output/Restart from and what differs (exit 2).
import subprocess
from anvil_test import ANVIL, SOURCE_DIR, WORK_DIR
def refused(scene, sets, expected, what):
    cmd = [ANVIL, os.path.join(SOURCE_DIR, scene)]
    for x in sets:
        cmd += ["--set", x]
    p = subprocess.run(cmd, capture_output=True, text=True)
    lines = p.stderr.strip().splitlines()
    check(p.returncode == 2 and len(lines) == 1 and "Output/Restart from" in p.stderr and expected in p.stderr
          and "Timer" not in p.stdout + p.stderr,
          "%s refused: exit %d, %r" % (what, p.returncode, p.stderr.strip()))
out_mid, _, _ = run("tests/plastic_block.prm", heat + ["Time/End time=0.5"], name="ckpt_heat_mid")
ck = out_mid + "/checkpoint"
ckpt = "Output/Restart from=" + ck
refused("tests/plastic_block.prm", heat[1:] + ["Physics/Coupling=isothermal split", ckpt],
        "Physics/Coupling = 'adiabatic split', this scene has 'isothermal split'", "another coupling scheme")
refused("prm/two_blocks.prm", ["Physics/Coupling=adiabatic split", ckpt],
        "Bodies/Names = 'body', this scene has 'lower,upper'", "a checkpoint of a scene with other bodies")
# A restart into the directory of a run that went further (a run killed after
# its last checkpoint) truncates every history at the checkpoint's time: no
# time twice, none going back, as many rows as the uninterrupted run.
import shutil
shutil.copytree(out_full, out_full + "_again", dirs_exist_ok=True)
_, again, _ = run("tests/plastic_block.prm", heat + ["Output/Restart from=" + ck],
                  name=os.path.basename(out_full) + "_again")
for f in ("reactions.csv", "energy.csv", "probes.csv", "thermal.csv"):
    a, b = read_csv(os.path.join(out_full, f)), read_csv(os.path.join(out_full + "_again", f))
    times = b["time"]
    check(len(times) == len(a["time"]) and all(t1 < t2 for t1, t2 in zip(times, times[1:])),
          "%s after a restart into a longer run's directory: %d rows (uninterrupted %d), times increasing"
          % (f, len(times), len(a["time"])))
close(again["quantities_of_interest"]["F"], full["quantities_of_interest"]["F"], 1e-7,
      "and the same final force")

state = os.path.join(ck, "state.txt")
text = open(state).read()
open(state, "w").write(re.sub(r"anvil-checkpoint \d+", "anvil-checkpoint 1", text, count=1))
refused("tests/plastic_block.prm", heat + [ckpt], "checkpoint format 1", "a checkpoint of another format")
open(state, "w").write("garbage\n" * 3)
refused("tests/plastic_block.prm", heat + [ckpt], "holds no anvil checkpoint", "a garbage state file")
open(state, "w").write(text.replace("\ntime ", "\ntime 1e99999 x", 1))
p = subprocess.run([ANVIL, os.path.join(SOURCE_DIR, "tests/plastic_block.prm")] +
                   sum([["--set", x] for x in heat + [ckpt]], []), capture_output=True, text=True)
check(p.returncode == 2 and len(p.stderr.strip().splitlines()) == 1 and "'time'" in p.stderr,
      "a checkpoint entry that is not a number: one line naming it, exit 2 (%r)" % p.stderr.strip())
open(state, "w").write(text)

# 4. The scene's step applies after a restart, not the checkpoint's.
big = base + ["Time/Time step=0.25", "Time/Maximum time step=0.25", "Time/End time=0.25"]
out_big, _, _ = run("prm/necking_bar.prm", big, name="ckpt_big_step")
small = ["Output/Field interval=0", "Time/Time step=0.05", "Time/End time=0.4",
         "Output/Restart from=" + out_big + "/checkpoint"]
_, _, stdout = run("prm/necking_bar.prm", small, name="ckpt_big_step")
first = [l for l in stdout.splitlines() if l.startswith("anvil: restarting")]
check(len(first) == 1 and "with dt = 0.05 s (saved step 0.25 s" in first[0],
      "the restart says it continues with the scene's step: %r" % (first[:1],))
times = read_csv(out_big + "/reactions.csv")["time"]
gaps = [b - a for a, b in zip(times, times[1:]) if a >= 0.25 - 1e-12]
check(len(gaps) == 3 and all(abs(g - 0.05) < 1e-12 for g in gaps),
      "after the restart at 0.25 s the steps are 0.05 s: %s" % gaps)
finish()

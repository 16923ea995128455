"""Nothing computed is lost: checkpoint and restart.

 1. The necking bar run to t = 0.5 and resumed from its checkpoint on two
    processes ends with the answer of the uninterrupted run (quantities of
    interest to 1e-9 relative, the same reaction history, the same plastic
    work).
 2. A run that cannot go on (a plastic-increment limit no step can meet, and
    no room to cut back) exits with status 3, says why, and leaves its last
    converged fields, summary.json (status failed) and a checkpoint; resumed
    from that checkpoint without the limit it completes with the same answer."""
import os
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
finish()

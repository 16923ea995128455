"""The stability map of the study tool (anvil --study, Mode = stability)
reproduces the one-dof prediction of doc/thermal.md for the splits
(tests/study/split_limit.prm, the setting of tests/split_stability.py):

 - isothermal split, heat capacity at constant volume: d_n = -tau_v r d_(n-1),
   stable for tau_v r < 1, so the largest stable tau_r = tau_v r is 1; the
   bisection (7 steps on [0.5, 10], log scale) must find it within 10 %;
 - adiabatic split: stable for every tau, so no limit over the range;
 - monolithic (backward Euler on the coupled system, no lag): no limit either.
"""
import csv
import os
import subprocess

from anvil_test import ANVIL, SOURCE_DIR, WORK_DIR, check, close, finish

out = os.path.join(WORK_DIR, "output", "study_split_limit")
p = subprocess.run([ANVIL, "--study", os.path.join(SOURCE_DIR, "tests", "study", "split_limit.prm"),
                    "--output", out], capture_output=True, text=True)
print(p.stdout.strip().split("\n")[-1])
check(p.returncode == 0, "anvil --study exits with 0 (%d) %s" % (p.returncode, p.stderr.strip()))
with open(os.path.join(out, "stability.csv")) as f:
    rows = {r["scheme"]: r for r in csv.DictReader(f)}
iso, adi = rows["isothermal split"], rows["adiabatic split"]
print("  isothermal split: stable at tau_r = %s, unstable at %s (%s)" % (iso["largest_stable_tau_r"],
                                                                       iso["smallest_unstable_tau_r"], iso["reason"]))
check(iso["state"] == "limit", "isothermal split: a limit inside the range (%s)" % iso["state"])
close(float(iso["estimate"]), 1.0, 0.10, "isothermal split: largest stable tau_v r, predicted 1/r x r = 1")
close(float(iso["largest_stable_tau_r"]), 1.0, 0.10, "isothermal split: largest tau_v r found stable")
close(float(iso["smallest_unstable_tau_r"]), 1.0, 0.10, "isothermal split: smallest tau_v r found unstable")
check(adi["state"] == "stable over the range",
      "adiabatic split: no limit up to tau_v r = 10 (%s, %s trial(s))" % (adi["state"], adi["trials"]))
mono = rows["monolithic"]
check(mono["state"] == "stable over the range",
      "monolithic: no limit up to tau_v r = 10 (%s, %s trial(s))" % (mono["state"], mono["trials"]))
check(os.path.getsize(os.path.join(out, "stability.png")) > 0, "stability.png written")
finish()

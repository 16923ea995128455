"""The study tool's physics cost mode and its bad input (anvil --study):

 1. physics cost: the Perzyna relaxation (tests/study/relaxation.prm) with its
    viscosity switched off (Model = J2, h = 0) holds the yield stress exactly,
    sigma = sigma_0 = 300 MPa, and the table gives its change against the
    viscous run;
 2. bad input (a ladder entry the scene does not have, a reference quantity
    that does not exist, an empty ladder or level, paired entries of different
    lengths, a quantity of interest the scene lacks, no reference): one line
    naming the study file, exit status 2, before any run (no runs folder).
"""
import csv
import os
import shutil
import subprocess

from anvil_test import ANVIL, SOURCE_DIR, WORK_DIR, check, finish

STUDY = os.path.join(SOURCE_DIR, "tests", "study", "tool_checks.prm")
BASE = os.path.join(WORK_DIR, "output", "study_input")
shutil.rmtree(BASE, ignore_errors=True)
os.makedirs(BASE)


def study(path, out, extra=()):
    return subprocess.run([ANVIL, "--study", path, "--output", out] + list(extra), capture_output=True, text=True)


# 1. Physics cost: viscosity off.
cost = os.path.join(BASE, "physics_cost.prm")
with open(cost, "w") as f:
    f.write("subsection Study\n  set Scene = %s\n  set Mode = physics cost\nend\n"
            "subsection Quantities\n  set s = summary\nend\n"
            "subsection Physics cost\n  subsection no viscosity\n    set Bodies/bar/Material/Model = J2\n  end\nend\n"
            % os.path.join(SOURCE_DIR, "tests", "study", "relaxation.prm"))
p = study(cost, os.path.join(BASE, "physics_cost"))
with open(os.path.join(BASE, "physics_cost", "physics_cost.csv")) as f:
    rows = {r["variant"]: r for r in csv.DictReader(f)}
base, j2 = rows["baseline (the scene)"], rows["no viscosity"]
print("  physics cost: viscous s = %s MPa, rate-independent s = %s MPa, change %s, wall x%s"
      % (base["s"], j2["s"], j2["change_s"], j2["wall_time_ratio"]))
check(p.returncode == 0 and abs(float(j2["s"]) - 300) < 1e-6 * 300,
      "physics cost: without viscosity the bar holds sigma_0 = 300 MPa (%s)" % j2["s"])
check(abs(float(j2["change_s"]) - (float(j2["s"]) - float(base["s"]))) < 1e-9 * 300,
      "physics cost: change = value - baseline value")

# 2. Bad input.
with open(STUDY) as f:
    text = f.read().replace("relaxation.prm", os.path.join(SOURCE_DIR, "tests", "study", "relaxation.prm"))
cases = [("ladder entry the scene lacks", text.replace("set Time/Time step = 0.1", "set Time/Tim step = 0.1"),
          "Tim step"),
         ("reference quantity that does not exist", text.replace("  set s = 300", "  set sigma = 300"), "sigma"),
         ("empty ladder", text.replace("set Time/Time step = 0.1 | 0.05", "set Time/Time step ="), "empty"),
         ("empty level", text.replace("0.1 | 0.05", "0.1 | | 0.05"), "empty"),
         ("paired entries of different lengths",
          text.replace("set Time/Time step = 0.1 | 0.05",
                       "set Time/Time step = 0.1 | 0.05\n  set Time/End time = 1 | 2 | 3"), "levels"),
         ("quantity of interest the scene lacks", text.replace("set s = summary", "set s = summary s_max"), "s_max"),
         ("no reference", text[:text.index("subsection Reference")], "Reference")]
cases = [c + ((),) for c in cases]
cases.append(("--set of a study entry", text, "Concurrent runs", ("--set", "Study/Concurrent runs=1")))
for n, (what, body, word, extra) in enumerate(cases):
    path = os.path.join(BASE, "bad_%d.prm" % n)
    with open(path, "w") as f:
        f.write(body)
    out = os.path.join(BASE, "bad_%d" % n)
    p = study(path, out, extra)
    lines = [l for l in p.stderr.split("\n") if l.strip()]
    print("  %s: %s" % (what, lines[0] if lines else ""))
    check(p.returncode == 2 and len(lines) == 1 and path in lines[0] and word in lines[0]
          and not os.path.exists(os.path.join(out, "runs")),
          "%s: exit 2 (%d), one line naming the file and '%s', no run" % (what, p.returncode, word))
finish()

"""The material-point driver's files (issue 16):

 1. a scene's material block, copied verbatim from prm/necking_bar_thermal.prm
    (its Elasticity, Hardening with thermal softening, and Thermal
    subsections), is accepted; the point in uniaxial stress follows the
    saturation law sigma = s0 + h e + (s_inf - s0)(1 - exp(-delta e)) at T0
    (theta = 1), with sxx = E (exx - e) (isochoric flow);
 2. Output/File and Output/Summary are resolved against the .prm file's
    directory, not the working directory;
 3. the summary (JSON) is written beside the CSV, says 'completed', carries
    units, and its final state is the CSV's last row; a run that stops
    writes it too, with 'failed: ...' naming the step.
"""
import json
import math
import os
import shutil
import subprocess

from anvil_test import ANVIL, SOURCE_DIR, WORK_DIR, read_csv, check, close, finish

OUT = os.path.join(WORK_DIR, "output", "material_point_files")
shutil.rmtree(OUT, ignore_errors=True)
os.makedirs(OUT)


def material_block(scene):
    """The lines of Bodies/<body>/Material in @p scene, from 'subsection Material' to its 'end'."""
    lines = open(scene).read().splitlines()
    start = next(i for i, l in enumerate(lines) if l.strip() == "subsection Material")
    depth = 0
    for i in range(start, len(lines)):
        word = lines[i].split("#")[0].strip()
        if word.startswith("subsection"):
            depth += 1
        elif word == "end":
            depth -= 1
            if depth == 0:
                return lines[start:i + 1]
    raise SystemExit("no end of the Material block in " + scene)


def run_driver(prm, cwd, expect=0):
    p = subprocess.run([ANVIL, "--material-point", prm], capture_output=True, text=True, cwd=cwd)
    if p.returncode != expect:
        print(p.stdout, p.stderr)
        raise SystemExit("anvil --material-point %s exited with %d (expected %d)" % (prm, p.returncode, expect))
    return p


# ------------------------------------------------------------ 1. a scene's block, 2. paths
block = material_block(os.path.join(SOURCE_DIR, "prm", "necking_bar_thermal.prm"))
check(any("subsection Thermal" == l.strip() for l in block),
      "the copied block has the scene's Thermal subsection (%d lines)" % len(block))
prm_dir = os.path.join(OUT, "driver_files")
run_dir = os.path.join(OUT, "elsewhere")
os.makedirs(prm_dir)
os.makedirs(run_dir)
prm = os.path.join(prm_dir, "from_scene.prm")
with open(prm, "w") as f:
    f.write("\n".join(block) + "\n")
    f.write("subsection Path\n  set End time = 1\n  set Steps = 200\n  set Strain = exx: 0.2*t\n"
            "  set Temperature = 293\nend\nsubsection Output\n  set File = results/point.csv\nend\n")
p = run_driver(prm, run_dir)
print("  " + p.stdout.strip())
csv_path = os.path.join(prm_dir, "results", "point.csv")
summary_path = os.path.join(prm_dir, "results", "point.summary.json")
check(os.path.exists(csv_path), "Output/File = results/point.csv is written beside the .prm: " + csv_path)
check(not os.path.exists(os.path.join(run_dir, "results")),
      "nothing is written relative to the working directory")
check(os.path.exists(summary_path), "the summary is written beside the CSV: " + summary_path)

E, s0, h, s_inf, delta = 206900.0, 450.0, 129.24, 715.0, 16.93
hist = read_csv(csv_path)
worst_yield = worst_elastic = 0.0
plastic_rows = 0
for i in range(1, len(hist["step"])):
    e = hist["equivalent_plastic_strain"][i]
    if e <= 0:
        continue
    plastic_rows += 1
    law = s0 + h * e + (s_inf - s0) * (1 - math.exp(-delta * e))
    worst_yield = max(worst_yield, abs(hist["von_mises"][i] - law) / law)
    worst_elastic = max(worst_elastic, abs(hist["sxx"][i] - E * (hist["exx"][i] - e)) / abs(hist["sxx"][i]))
check(plastic_rows > 150, "the point yields (%d plastic steps of 200)" % plastic_rows)
check(worst_yield < 1e-9, "von Mises = saturation law at T0 at every plastic step: worst relative error %.2e (tolerance 1e-9)" % worst_yield)
check(worst_elastic < 1e-9, "sxx = E (exx - eps_p) at every plastic step: worst relative error %.2e (tolerance 1e-9)" % worst_elastic)

# ------------------------------------------------------------ 3. the summary
with open(summary_path) as f:
    s = json.load(f)
check(s.get("status") == "completed" and s.get("steps") == 200 and s.get("model") == "J2",
      "summary: status %s, %s steps, model %s" % (s.get("status"), s.get("steps"), s.get("model")))
close(s["stress"]["sxx"], hist["sxx"][-1], 1e-9, "summary: final sxx (the CSV's last row)")
close(s["equivalent_plastic_strain"], hist["equivalent_plastic_strain"][-1], 1e-9,
      "summary: final equivalent plastic strain")
close(s["temperature"], 293.0, 1e-12, "summary: final temperature")
units = s.get("units", {})
check(units.get("stress") == "MPa" and units.get("temperature") == "K" and units.get("time") == "s",
      "summary: units %s" % units)

# A run that stops (the yield stress softens to zero at 293 + 1/0.002 = 793 K):
# the summary says so and keeps the last step done.
with open(prm) as f:
    text = f.read()
text = text.replace("set Temperature = 293", "set Temperature = 293 + 600*t")
text = text.replace("results/point.csv", "results/soft.csv")
bad = os.path.join(prm_dir, "softens.prm")
with open(bad, "w") as f:
    f.write(text)
p = subprocess.run([ANVIL, "--material-point", bad], capture_output=True, text=True, cwd=run_dir)
with open(os.path.join(prm_dir, "results", "soft.summary.json")) as f:
    s = json.load(f)
print("  exit %d, %s" % (p.returncode, p.stderr.strip().splitlines()[-1] if p.stderr.strip() else ""))
check(p.returncode != 0 and s["status"].startswith("failed: material point, step"),
      "a run that stops: exit %d, summary status '%s'" % (p.returncode, s["status"][:90]))
check(0 < s["steps"] < 200 and s["temperature"] < 793,
      "a run that stops: the summary keeps the last step done (%d, T = %.1f K)" % (s["steps"], s["temperature"]))
finish()

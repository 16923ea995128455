"""Units, boundary displacements, quantities of interest and the run's last lines.

1. Every CSV column that is a physical quantity carries its unit in the header
   ("time [s]", "left_Fx [N]"); counts do not; tests read columns by name with
   or without it (anvil_test.read_csv).
2. reactions.csv: each boundary's mean displacement beside its force. A face
   driven by ux = 0.1 t moves by exactly 0.1 t, a fixed one by 0 (the
   prescription, independent of the solution).
3. Quantities of interest: max(temperature) over the nodal values equals the
   Dirichlet value 393 K of heat_half_space (a cell average cannot reach it);
   a difference of two probes equals the difference of their columns in
   probes.csv; a sum of quantities of different units is bad input (exit 2).
   Each result is printed with its unit and summary.json has a "units" map.
4. The progress line shows the end time and the percentage; the run ends with
   "results in <dir>: ..." naming the files written; memory_per_dof_bytes
   counts only the memory above the libraries' baseline.
"""
import re

from anvil_test import run, read_csv, check, close, finish

# 1-2. Mechanics: a unit square pulled by ux = 0.1 t on its right face.
bc = "Boundary conditions/Displacement=left: ux = 0; bottom: uy = 0; right: ux = 0.1*t"
out, s, stdout = run("tests/homogeneous.prm", [bc, "Output/Verbosity=normal", "Output/Probes=c: 0.5, 0.5",
                                               "Output/Quantities of interest=F: reaction(right, x); "
                                               "stretch: probe(c, ux) - probe(c, uy) + 1"],
                     name="output_units_mech")
with open(out + "/reactions.csv") as f:
    header = f.readline().strip().split(",")
print("  reactions.csv: " + ", ".join(header[:8]) + ", ...")
check(header[:2] == ["step", "time [s]"], "reactions.csv starts with step, time [s]")
check("right_ux [mm]" in header and "right_Fx [N]" in header
      and header.index("right_ux [mm]") < header.index("right_Fx [N]"),
      "reactions.csv: right_ux [mm] beside right_Fx [N]")
r = read_csv(out + "/reactions.csv")
err = max(abs(u - 0.1 * t) for u, t in zip(r["right_ux"], r["time [s]"]))
check(err < 1e-12, "right face moves by 0.1 t (largest difference %.1e mm)" % err)
check(max(abs(u) for u in r["left_ux"]) < 1e-15, "left face (ux = 0) does not move in x")
check(r.units["right_Fx"] == "N" and r.units["step"] == "", "units read from the header")
for name in ("probes.csv", "energy.csv", "newton.csv"):
    with open(out + "/" + name) as f:
        cols = f.readline().strip().split(",")
    bare = [c for c in cols if " [" not in c]
    check(all(c in ("step", "iteration", "converged") for c in bare),
          "%s: every physical column has a unit (without: %s)" % (name, ", ".join(bare)))
p = read_csv(out + "/probes.csv")
q = s["quantities_of_interest"]
close(q["stretch"], p["c_ux"][-1] - p["c_uy"][-1] + 1, 1e-10, "probe(c, ux) - probe(c, uy) + 1")
check(s["units"].get("F") == "N" and s["units"].get("stretch") == "mm",
      "summary.json units: F in %s, stretch in %s" % (s["units"].get("F"), s["units"].get("stretch")))
check(re.search(r"^  F = \S+ N$", stdout, re.M) is not None, "QoI printed with its unit (F = ... N)")

# 4. The progress line and the last line.
steps = [l for l in stdout.splitlines() if l.startswith("step")]
check(steps and re.search(r"t = \S+ / 1\.000e\+00 s \(100\.0 %\)", steps[-1]) is not None,
      "progress line with end time and percentage: '%s'" % (steps[-1][:60] if steps else ""))
last = stdout.strip().splitlines()[-1]
print("  " + last)
check(last.startswith("anvil: results in " + out + ": ") and "summary.json" in last
      and "reactions.csv" in last and "fields/ (" in last, "last line lists the results")
raw = s["peak_memory_MB"] * 2**20 / s["dofs"]
print("  memory per dof: %.0f B above the baseline (%.0f B with it)" % (s["memory_per_dof_bytes"], raw))
check(0 <= s["memory_per_dof_bytes"] < raw, "memory_per_dof_bytes has the baseline subtracted")

# 3. Heat: extrema over the nodal values.
out, s, stdout = run("prm/heat_half_space.prm", [
    "Output/Quantities of interest=T_max: max(temperature); "
    "dT12: probe(p1, temperature) - probe(p2, temperature)"], name="output_units_heat")
q = s["quantities_of_interest"]
close(q["T_max"], 393.0, 1e-12, "max(temperature) over the nodes = the Dirichlet value 393 K")
p = read_csv(out + "/probes.csv")
close(q["dT12"], p["p1_temperature"][-1] - p["p2_temperature"][-1], 1e-10,
      "probe(p1) - probe(p2) = difference of the probes.csv columns")
check(s["units"]["T_max"] == "K" and re.search(r"^  T_max = 393 K  \(max\(temperature\) over nodal values\)$", stdout, re.M) is not None,
      "temperature results in K, and the printout says what the extremum runs over")
with open(out + "/thermal.csv") as f:
    check("time_step [s]" in f.readline(), "thermal.csv: time_step [s]")

# 3. Bad input: a sum of a force and a displacement (run() stops unless exit 2).
run("tests/homogeneous.prm", [bc, "Output/Probes=c: 0.5, 0.5",
                                        "Output/Quantities of interest=bad: reaction(right, x) + probe(c, ux)"],
    name="output_units_bad", expect_status=2)
print("PASS  reaction + displacement is refused (exit 2)")
finish()

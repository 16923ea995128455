"""The quarter-cylinder forming (prm/quarter_cylinder_forming.prm, 693 K) with
its temperature prescribed (the scene: Physics/Coupling = prescribed
temperature, no heat equation) against the same scene solving the heat
equation (isothermal split, ARKode) with that temperature imposed on all four
faces of the sheet (issue 13, "Prescribed-temperature scene vs the same scene
solving the heat equation").

Independent expectations:
- Interior temperature: with no plastic heating (Taylor-Quinney 0) the
  solved field lags the faces only by conduction across the half-thickness
  h/2 = 0.5 mm: dT ~ rho c (h/2)^2 / (2 k) * |dT/dt| = 2.394 * 0.25 / 240 *
  |dT/dt| (AA5083: k = 120 mW/(mm K), rho c = 2.66e-9 * 9e8): 3.3e-3 K on
  the heating ramp (400 K / 300 s), 1.0e-2 K on the cooling one (400 K /
  100 s; measured 0.012 K). Checked < 0.05 K at a mid-thickness probe.
- Shape: the two runs then differ by the split (the mechanics of a step sees
  the temperature of the step's start) and by their step sequences, which
  adapt to Newton's work. The scene's own time-step error bounds both: the
  springback (free-end rotation, end of hold minus end) of the prescribed
  scene moves by 0.6 % over its Maximum time step ladder 600 -> 75 s
  (9.6616, 9.6356, 9.6161, 9.6032 deg; studies/quarter_cylinder_forming.prm,
  doc/studies/quarter_cylinder_forming.md). Checked within 1 %; the final
  rotation (77.5 deg) within 0.05 deg.
Prints the cost of each (steps, Newton iterations, ARKode steps, wall
time) and their ratio."""
import math
import os

from anvil_test import run, read_csv, check, close, finish

RAMP = "if(t < 300, t/300, if(t < 3000, 1, max(0, (3100 - t)/100)))"
F = "293 + 400*" + RAMP
PROBES = "Output/Probes=tip_bottom: 0, 0; tip_top: 0, 1; mid_core: 123.37, 0.5"
COMMON = ["Output/Figure list=", PROBES]


def ramp(t):
    return 293 + 400 * (t / 300 if t < 300 else (1 if t < 3000 else max(0, (3100 - t) / 100)))


def rotation(c, i):
    dx = c["tip_top_ux"][i] - c["tip_bottom_ux"][i]
    dy = 1 + c["tip_top_uy"][i] - c["tip_bottom_uy"][i]
    return -math.degrees(math.atan2(dx, dy))


def springback(out):
    c = read_csv(os.path.join(out, "probes.csv"))
    hold = max(i for i, t in enumerate(c["time"]) if t <= 3000 * (1 + 1e-12))
    end = len(c["time"]) - 1
    return rotation(c, hold) - rotation(c, end), rotation(c, end), c


out_p, s_p, _ = run("prm/quarter_cylinder_forming.prm", COMMON, name="forming_prescribed")
out_h, s_h, _ = run("prm/quarter_cylinder_forming.prm", COMMON + [
    "Physics/Coupling=isothermal split", "Heat/Initial temperature=293",
    "Heat/Boundary conditions/Temperature=left: %s; right: %s; top: %s; bottom: %s" % (F, F, F, F),
    "Bodies/sheet/Material/Elasticity/Taylor-Quinney coefficient=0",
    "Bodies/sheet/Material/Elasticity/Heat capacity=9e8",
    "Bodies/sheet/Material/Thermal/Conductivity=120"], name="forming_solved_heat")

sb_p, end_p, _ = springback(out_p)
sb_h, end_h, c_h = springback(out_h)
lag = max(abs(T - ramp(t)) for t, T in zip(c_h["time"], c_h["mid_core_temperature"]))
print("largest |T - T_prescribed| at mid-thickness: %.3g K" % lag)
check(lag < 0.05, "solved temperature follows the faces within 0.05 K (conduction lag <= 1.0e-2 K)")
close(sb_h, sb_p, 0.01, "springback with the heat equation [deg] (prescribed: %.4f)" % sb_p)
close(end_h, end_p, 0.0, "final free-end rotation [deg]", atol=0.05)

arkode = sum(read_csv(os.path.join(out_h, "thermal.csv"))["arkode_steps"])
print("cost: prescribed %d steps, %d Newton, %.2f s; solved %d steps, %d Newton, %d ARKode "
      "steps, %.2f s; ratio %.2f" % (s_p["steps"], s_p["newton_iterations"], s_p["wall_time"],
                                     s_h["steps"], s_h["newton_iterations"], arkode,
                                     s_h["wall_time"], s_h["wall_time"] / s_p["wall_time"]))
finish()

"""The energy audit can fail (doc/energy_audit.md).

Two balances, each side computed by its own route:
  work:   W_ext + K0 = K + W_sigma + W_contact   (nodal forces x displacement
          increments against the quadrature sum of sigma_bar : d_eps dv_half)
  stress: W_sigma = dE_el + W_p,flow + W_th - V_hypo + W_Fbar
          (elastic energy from the stresses, plastic work from the flow rule)

 a. Every scene of the list ends, and passes every step, with both errors
    below 0.5 % (SCENES; `--all` runs every mechanical scene of prm/, full
    length: the `energy_audit_all` test, label long).
 b. The audit detects what is left out: with ANVIL_AUDIT_OMIT=TERM (test only)
    one term is dropped from the sums and the balance it belongs to fails by
    more than the bound.
 c. The work balance converges with the step at the scheme's order (second:
    mid-point kinematics, trapezoidal work) on the twisted bar, and a coarse
    step exceeds the bound.

Usage: energy_audit.py [--all]"""
import os
import sys
from anvil_test import run, read_csv, check, finish

BOUND = 5e-3
QUIET = ["Output/Field interval=0"]
# Cheap scenes at full length, the expensive ones shortened (the thermal
# necking bar to its first 2 s, the forming and crushing scenes are --all only).
SCENES = [("prm/cantilever.prm", []),
          ("prm/bimaterial_gmsh.prm", []),
          ("prm/thick_cylinder.prm", []),
          ("prm/punch.prm", []),
          ("prm/necking_bar.prm", []),
          ("prm/twisted_bar_3d.prm", []),
          ("prm/necking_bar_thermal.prm", ["Time/End time=2"]),
          ("prm/two_blocks.prm", [])]
if "--all" in sys.argv:
    here = os.environ.get("ANVIL_SOURCE_DIR", os.path.join(os.path.dirname(__file__), ".."))
    SCENES = [("prm/" + f, []) for f in sorted(os.listdir(os.path.join(here, "prm")))
              if f.endswith(".prm") and f != "heat_half_space.prm"]  # thermal only: no mechanics


def column(table, name):
    """A column by its name before any unit (' [N mm]')."""
    for k, v in table.items():
        if k.split(" [")[0] == name:
            return v
    raise KeyError(name)


def audit(scene, sets, name, omit=None):
    if omit:
        os.environ["ANVIL_AUDIT_OMIT"] = omit
    try:
        out, s, _ = run(scene, QUIET + sets, name=name)
    finally:
        os.environ.pop("ANVIL_AUDIT_OMIT", None)
    e = read_csv(out + "/energy.csv")
    return s["energy"], column(e, "balance_error"), column(e, "stress_balance_error")


# a. every scene within the bound, at the end and at every step.
for scene, sets in SCENES:
    name = "energy_audit_" + os.path.basename(scene)[:-4]
    en, work_rows, stress_rows = audit(scene, sets, name)
    print("  %-32s W_ext %.6g  K0 %.4g  K %.4g  W_sigma %.6g  W_c %.4g | dE_el %.4g  W_p %.6g  "
          "W_th %.4g  V_hypo %.4g  W_Fbar %.4g" % (os.path.basename(scene), en["external_work"],
          en["initial_kinetic_energy"], en["kinetic_energy"], en["stress_work"], en["contact_work"],
          en["elastic_energy"], en["flow_plastic_work"], en["thermal_work"],
          en["hypoelastic_volume_work"], en["f_bar_work"]))
    check(en["balance_error"] < BOUND and max(work_rows) < BOUND,
          "%s: work balance %.2e at the end, %.2e at worst over %d steps (< %g)"
          % (scene, en["balance_error"], max(work_rows), len(work_rows) - 1, BOUND))
    check(en["stress_balance_error"] < BOUND and max(stress_rows) < BOUND,
          "%s: stress balance %.2e at the end, %.2e at worst (< %g)"
          % (scene, en["stress_balance_error"], max(stress_rows), BOUND))

if "--all" not in sys.argv:
    # b. a term left out is seen: each balance fails by more than the bound.
    short = ["Time/End time=0.2"]
    for omit, scene, which in (("plastic_work", "prm/necking_bar.prm", "stress_balance_error"),
                               ("stress_work", "prm/necking_bar.prm", "balance_error"),
                               ("hypoelastic_volume_work", "prm/bimaterial_gmsh.prm",
                                "stress_balance_error"),
                               ("thermal_work", "prm/necking_bar_thermal.prm",
                                "stress_balance_error")):
        sets = short if "necking_bar.prm" in scene else \
               ["Time/End time=1"] if "thermal" in scene else []
        en, _, _ = audit(scene, sets, "energy_audit_omit_" + omit, omit)
        check(en[which] > BOUND, "without %s (%s): %s = %.2e > %g"
              % (omit, os.path.basename(scene), which, en[which], BOUND))

    # c. the work balance against the step: second order; a coarse step fails.
    errors = []
    for n in (5, 10, 20, 40):
        en, _, _ = audit("prm/twisted_bar_3d.prm", ["Time/Time step=%g" % (1.0 / n)],
                         "energy_audit_twist_%d" % n)
        errors.append(en["balance_error"])
        print("  twisted bar, %2d steps: work balance %.3e, stress balance %.3e"
              % (n, en["balance_error"], en["stress_balance_error"]))
    orders = [(errors[i] / errors[i + 1]) for i in range(len(errors) - 1)]
    print("  error ratios per halving: " + ", ".join("%.2f" % r for r in orders))
    check(all(3.0 < r < 5.0 for r in orders[1:]),
          "work balance converges at second order in the step (ratios %s, expected ~4)"
          % ", ".join("%.2f" % r for r in orders))
    check(errors[0] > BOUND, "5 steps for 90 degrees of twist: the work balance fails (%.2e > %g)"
          % (errors[0], BOUND))
finish()

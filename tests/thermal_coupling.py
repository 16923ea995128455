"""Isothermal split, first coupled checks (issue 5 in progress):
an insulated unit square of J2 metal (linear hardening) stretched
isochorically by 20 % (x -> 1.2 x, y -> y / 1.2; every boundary node follows
the homogeneous motion).
The heat equation receives chi W_irr from the mechanics at every step:

 - the heat content gained equals chi times the plastic work the mechanics
   did (the coupling transfers all of it), to 1e-6;
 - both equal the closed form chi V (s0 p + h p^2 / 2) for the uniform
   plastic strain p, to 0.5 % (V: the current volume, J ~ 1)."""
from anvil_test import run, check, close, finish

chi, s0, h = 0.9, 300.0, 1000.0
sets = ["Bodies/body/Material/Model=J2",
        "Bodies/body/Material/Hardening/Initial yield stress=%g" % s0,
        "Bodies/body/Material/Hardening/Hardening modulus=%g" % h,
        "Bodies/body/Material/Elasticity/Young's modulus=200000",
        "Bodies/body/Material/Elasticity/Taylor-Quinney coefficient=%g" % chi,
        "Physics/Heat=true", "Heat/Initial temperature=293",
        "Mechanics/Newton/Residual tolerance=1e-10", "Mechanics/Newton/Absolute residual tolerance=0",
        "Boundary conditions/Displacement=" + "; ".join("%s: ux = 0.2*t*x, uy = (1/(1 + 0.2*t) - 1)*y" % b
                                                 for b in ("left", "right", "bottom", "top")),
        "Output/Quantities of interest=p: max(equivalent_plastic_strain); p_min: min(equivalent_plastic_strain); J: mean(J)"]
out, s, _ = run("tests/homogeneous.prm", sets, name="thermal_coupling_heating")
q = s["quantities_of_interest"]
heat = s["heat"]["heat_content_change"]
wp = s["energy"]["plastic_work"]
print("  plastic strain %.6f (uniform: min %.6f), heat gained %.8f mJ, chi W_p %.8f mJ, ARKode steps %d"
      % (q["p"], q["p_min"], heat, chi * wp, s["heat"]["arkode_internal_steps"]))
close(heat, chi * wp, 1e-6, "heat content gained = chi x plastic work (mJ per mm depth)")
p = q["p"]
close(heat, chi * q["J"] * 1.0 * (s0 * p + h * p * p / 2), 5e-3, "= chi V (s0 p + h p^2/2), closed form")
finish()

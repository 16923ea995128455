"""Loads: gravity and velocity-driven faces.

 - A block standing on its base under its own weight (gravity 9810 mm/s^2,
   rho = 7.8e-9 t/mm^3): the reaction of the base equals the weight rho g V
   (per mm of depth in plane strain; per ring in axisymmetry, 2 pi r weighted);
 - a face driven at a velocity v(t) = 0.02 (1 + t) mm/s moves by the integral
   0.02 (t + t^2/2) (the trapezoidal increments are exact for v linear in t)."""
import math
from anvil_test import run, check, close, finish

rho, g = 7.8e-9, 9810.0
common = ["Bodies/body/Material/Elasticity/Density=%g" % rho, "Mechanics/Gravity=0, -%g" % g,
          "Boundary conditions/Displacement=bottom: ux = 0, uy = 0", "Geometry/Random distortion=0",
          "Output/Quantities of interest=base: reaction(bottom, y)",
          # strains of 1e-7: the increments carry only 9 digits, the default tolerance fits
          "Mechanics/Newton/Residual tolerance=1e-8", "Mechanics/Newton/Absolute residual tolerance=0"]
_, s, _ = run("tests/homogeneous.prm", common, name="loads_gravity")
close(s["quantities_of_interest"]["base"], rho * g * 1.0, 1e-6, "plane strain: base reaction = weight (N/mm)")
_, s, _ = run("tests/homogeneous.prm", common + ["Mechanics/Two-dimensional model=axisymmetric",
                                                 "Geometry/Blocks=body: 1, 0, 2, 1, 4, 4"], name="loads_gravity_axi")
close(s["quantities_of_interest"]["base"], rho * g * math.pi * (2 * 2 - 1 * 1) * 1.0, 1e-6,
      "axisymmetric ring: base reaction = weight (N)")

_, s, _ = run("tests/homogeneous.prm", ["Boundary conditions/Displacement=bottom: ux = 0, uy = 0",
                                        "Boundary conditions/Velocity=top: uy = 0.02*(1 + t)",
                                        "Output/Probes=corner: 1, 1",
                                        "Output/Quantities of interest=top_uy: probe(corner, uy)"], name="loads_velocity")
close(s["quantities_of_interest"]["top_uy"], 0.02 * (1 + 0.5), 1e-10, "velocity-driven face: displacement = integral of v")
finish()

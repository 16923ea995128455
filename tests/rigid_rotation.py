"""Rigid rotation of a prestressed body: after a homogeneous stretch (t in [0, 1])
the stretched square is rotated rigidly by 90 degrees (t in [1, 2]) in several
increments. The Cauchy stress must co-rotate exactly, sigma = R sigma0 R^T, i.e.
sxx <-> syy swapped and sxy = 0, with no spurious stress (1e-10 relative)."""
from anvil_test import run, check, close, finish

disp = "; ".join(
    "%s: ux = cos(pi/2*max(t-1,0))*(1+0.2*min(t,1))*x - sin(pi/2*max(t-1,0))*(1-0.1*min(t,1))*y - x, "
    "uy = sin(pi/2*max(t-1,0))*(1+0.2*min(t,1))*x + cos(pi/2*max(t-1,0))*(1-0.1*min(t,1))*y - y" % b
    for b in ("left", "right", "bottom", "top"))
common = ["Boundary conditions/Displacement=" + disp, "Time/Time step=0.125"]
_, s0, _ = run("tests/homogeneous.prm", common + ["Time/End time=1"], name="rigid_rotation_prestress")
_, s1, _ = run("tests/homogeneous.prm", common + ["Time/End time=2"], name="rigid_rotation")
a, b = s0["quantities_of_interest"], s1["quantities_of_interest"]
scale = max(abs(a["sxx_max"]), abs(a["syy_max"]))
print("  prestress: sxx = %.12g syy = %.12g szz = %.12g" % (a["sxx_max"], a["syy_max"], a["szz_max"]))
print("  rotated:   sxx = %.12g syy = %.12g szz = %.12g sxy = %.3g" % (b["sxx_max"], b["syy_max"], b["szz_max"], b["sxy_max"]))
close(b["sxx_max"], a["syy_max"], 1e-10, "rotated stress_xx = prestress stress_yy", atol=1e-10 * scale)
close(b["syy_max"], a["sxx_max"], 1e-10, "rotated stress_yy = prestress stress_xx", atol=1e-10 * scale)
close(b["szz_max"], a["szz_max"], 1e-10, "stress_zz unchanged", atol=1e-10 * scale)
for c in ("sxy_max", "sxy_min"):
    check(abs(b[c]) <= 1e-10 * scale, "no spurious shear after rotation: %s = %.3e" % (c, b[c]))
for c in ("sxx", "syy"):
    check(abs(b[c + "_max"] - b[c + "_min"]) <= 1e-10 * scale, "rotated %s uniform" % c)
finish()

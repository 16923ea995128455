"""The material-point driver (anvil --material-point FILE) on a hypoelastic
point, E = 200000 MPa, nu = 0.3, against closed forms:

 1. uniaxial stress by strain control (exx = 0.01 t, every other component
    stress-free, found by the local Newton loop): sxx = E exx and
    eyy = ezz = -nu exx at every step (small increments add linearly);
 2. deformation-gradient control, a stretch in x then a rigid rotation by
    90 degrees: the stress co-rotates, sxx and syy swap;
 3. deformation-gradient control, simple shear F12 = gamma = 2t: the Jaumann
    closed form sxy = G sin(gamma), sxx = -syy = G (1 - cos(gamma)), with the
    second-order convergence of the Hughes-Winget update;
 4. bad input: exit status 2, one line on stderr naming the file, line and
    entry, and no CSV written.

The driver files are the shipped examples prm/material_point/*.prm (each of
which must also pass --check)."""
import glob
import math
import os
import subprocess

from anvil_test import ANVIL, SOURCE_DIR, WORK_DIR, read_csv, check, close, finish, run_point

E, nu = 200000.0, 0.3
G = E / (2 * (1 + nu))
OUT = os.path.join(WORK_DIR, "output", "material_point")
os.makedirs(OUT, exist_ok=True)


def example(name):
    return os.path.join(SOURCE_DIR, "prm", "material_point", name + ".prm")


def rel_error(value, expected):
    return abs(value - expected) / abs(expected)


# ------------------------------------------------------------ 1. uniaxial stress
path, out, _ = run_point(example("uniaxial_stress"))
print("  " + out.strip())
h = read_csv(path)
n = len(h["step"])
check(n == 101, "uniaxial stress: %d rows (t = 0 and 100 steps)" % n)
worst = {"sxx": 0.0, "eyy": 0.0, "ezz": 0.0, "free stress": 0.0}
for i in range(1, n):
    exx = h["exx"][i]
    worst["sxx"] = max(worst["sxx"], rel_error(h["sxx"][i], E * exx))
    worst["eyy"] = max(worst["eyy"], rel_error(h["eyy"][i], -nu * exx))
    worst["ezz"] = max(worst["ezz"], rel_error(h["ezz"][i], -nu * exx))
    worst["free stress"] = max(worst["free stress"], max(abs(h[c][i]) for c in ("syy", "szz", "sxy", "syz", "sxz")) / abs(h["sxx"][i]))
print("  final: exx = %.10g  sxx = %.10g (E exx = %.10g)  eyy = %.10g  ezz = %.10g (-nu exx = %.10g)"
      % (h["exx"][-1], h["sxx"][-1], E * h["exx"][-1], h["eyy"][-1], h["ezz"][-1], -nu * h["exx"][-1]))
close(h["exx"][-1], 0.01, 1e-12, "uniaxial stress: final exx")
for what, err in worst.items():
    check(err <= 1e-10, "uniaxial stress: max relative error of %s over all steps = %.3g (tolerance 1e-10)" % (what, err))
check(max(h["local_iterations"][1:]) <= 2, "uniaxial stress: at most %d local iterations per step" % max(h["local_iterations"][1:]))

# ------------------------------------------------------------ 2. stretch, then rigid rotation by 90 degrees
path, out, _ = run_point(example("stretch_rotate"))
print("  " + out.strip())
h = read_csv(path)
half = h["time"].index(0.5)
s_half = {c: h[c][half] for c in ("sxx", "syy", "szz", "exx", "eyy")}
s_end = {c: h[c][-1] for c in ("sxx", "syy", "szz", "sxy", "syz", "sxz", "exx", "eyy")}
print("  t = 0.5: sxx = %.12g  syy = %.12g  szz = %.12g" % (s_half["sxx"], s_half["syy"], s_half["szz"]))
print("  t = 1:   sxx = %.12g  syy = %.12g  szz = %.12g  sxy = %.3g" % (s_end["sxx"], s_end["syy"], s_end["szz"], s_end["sxy"]))
check(abs(s_half["sxx"] - s_half["syy"]) > 0.1 * abs(s_half["sxx"]), "rotation: the stretch gives a stress with sxx != syy")
close(s_end["sxx"], s_half["syy"], 1e-10, "rotation: final sxx (syy before the rotation)")
close(s_end["syy"], s_half["sxx"], 1e-10, "rotation: final syy (sxx before the rotation)")
close(s_end["szz"], s_half["szz"], 1e-10, "rotation: final szz (unchanged)")
close(s_end["sxy"], 0.0, 0, "rotation: final sxy", atol=1e-10 * abs(s_half["sxx"]))
close(s_end["eyy"], s_half["exx"], 1e-10, "rotation: the accumulated strain co-rotates too, final eyy")
# Before the rotation: uniaxial strain, sxx = (K + 4G/3) exx, syy = (K - 2G/3) exx.
K = E / (3 * (1 - 2 * nu))
close(s_half["sxx"], (K + 4 * G / 3) * s_half["exx"], 1e-10, "stretch: sxx = (K + 4G/3) exx")
close(s_half["syy"], (K - 2 * G / 3) * s_half["exx"], 1e-10, "stretch: syy = (K - 2G/3) exx")

# ------------------------------------------------------------ 3. simple shear to gamma = 2
gamma = 2.0
exact = {"sxy": G * math.sin(gamma), "sxx": G * (1 - math.cos(gamma)), "syy": -G * (1 - math.cos(gamma))}
errors = []
for steps in (500, 1000):
    path, out, _ = run_point(example("simple_shear"), ["Path/Steps=%d" % steps], name="simple_shear_%d" % steps)
    h = read_csv(path)
    err = max(rel_error(h[c][-1], exact[c]) for c in exact)
    print("  %4d steps: sxy = %.8f (G sin g = %.8f)  sxx = %.8f (G(1-cos g) = %.8f)  syy = %.8f  max relative error = %.3e"
          % (steps, h["sxy"][-1], exact["sxy"], h["sxx"][-1], exact["sxx"], h["syy"][-1], err))
    errors.append(err)
for c in exact:
    close(h[c][-1], exact[c], 1e-4, "simple shear, 1000 steps: %s" % c)
close(h["szz"][-1], 0.0, 0, "simple shear, 1000 steps: szz", atol=1e-10 * G)
order = math.log(errors[0] / errors[1], 2)
check(1.8 < order < 2.2, "simple shear: observed order of the Jaumann integration %.3f (expected 2)" % order)

# ------------------------------------------------------------ 4. bad input
def expect_error(what, prm, sets, pattern_parts):
    name = "bad_" + what.replace(" ", "_")
    path, out, err = run_point(prm, sets, name=name, expect_status=2)
    lines = [l for l in err.splitlines() if l.strip()]
    ok = len(lines) == 1 and all(p in lines[0] for p in pattern_parts) and not os.path.exists(path)
    check(ok, "bad input, %s: exit 2, %d line(s): %s" % (what, len(lines), " | ".join(lines)))


# A component both strain- and stress-controlled, in the file: file:line and the entry.
with open(example("uniaxial_stress")) as f:
    text = f.read().splitlines()
line = next(i for i, l in enumerate(text) if l.strip().startswith("set Stress"))
text[line] = "  set Stress      = eyy: 0; exx: 0"
bad = os.path.join(OUT, "both_strain_and_stress.prm")
with open(bad, "w") as f:
    f.write("\n".join(text) + "\n")
expect_error("strain and stress", bad, [], ["both_strain_and_stress.prm:%d:" % (line + 1), "'Path/Stress'", "exx"])
expect_error("no steps", example("uniaxial_stress"), ["Path/Steps=0"], ["--set", "'Path/Steps'"])
expect_error("unknown component", example("uniaxial_stress"), ["Path/Strain=exx: t; gxy: t"], ["'Path/Strain'", "gxy"])
expect_error("invalid expression", example("uniaxial_stress"), ["Path/Strain=exx: 0.01*tt"], ["'Path/Strain'", "0.01*tt"])
expect_error("F(0) not I", example("simple_shear"), ["Path/Deformation gradient=F11: 2 + t"], ["'Path/Deformation gradient'", "F(0)"])
expect_error("det F <= 0", example("simple_shear"), ["Path/Deformation gradient=F11: 1 - 2*t"], ["'Path/Deformation gradient'", "det F"])

# ------------------------------------------------------------ the template and the examples
p = subprocess.run([ANVIL, "--material-point", "--print-parameters"], capture_output=True, text=True)
check(p.returncode == 0 and "subsection Path" in p.stdout and "subsection Material" in p.stdout,
      "anvil --material-point --print-parameters prints the driver template")
for prm in sorted(glob.glob(os.path.join(SOURCE_DIR, "prm", "material_point", "*.prm"))):
    p = subprocess.run([ANVIL, "--material-point", prm, "--check"], capture_output=True, text=True, cwd=OUT)
    check(p.returncode == 0, "example %s passes --check %s" % (os.path.basename(prm), p.stderr.strip()))
finish()

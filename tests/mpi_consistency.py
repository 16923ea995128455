"""np = 1 and np = 2 give the same answer: the reaction-force history of every
named boundary, the probe history and the energy history (with the heat
columns when the scene has a temperature field) agree to solver tolerance
(relative 1e-8 of the largest value of the file); the temperature columns of
probes.csv and the heat columns of energy.csv are also checked against their
own scale.

Usage: mpi_consistency.py [scene.prm] [--set 'Section/Entry=value' ...]
(default scene prm/cantilever.prm; --set overrides are passed to both runs)."""
import sys
from anvil_test import run, read_csv, check, finish

scene, extra = "prm/cantilever.prm", []
args = sys.argv[1:]
while args:
    a = args.pop(0)
    if a == "--set" and args:
        extra.append(args.pop(0))
    elif a.startswith("--set="):
        extra.append(a[len("--set="):])
    else:
        scene = a
name = scene.replace("/", "_").replace(".prm", "")
sets = ["Output/Field interval=0", "Mechanics/Newton/Residual tolerance=1e-12"] + extra
o1, s1, _ = run(scene, sets, np=1, name=name + "_np1")
o2, s2, _ = run(scene, sets, np=2, name=name + "_np2")
check(s2["processes"] == 2, "second run used 2 processes")
check(s1["steps"] == s2["steps"], "same number of steps (%d, %d)" % (s1["steps"], s2["steps"]))


def compare(what, a, b, keys):
    """Largest difference over the columns keys, relative 1e-8 of their largest value."""
    scale = max(max(abs(x) for x in a[k]) for k in keys) or 1.0
    worst = max(abs(x - y) for k in keys for x, y in zip(a[k], b[k]))
    check(worst <= 1e-8 * scale, "%s: np=1 vs np=2 largest difference %.3e (scale %.3e)" % (what, worst, scale))


# The heat columns of energy.csv (the others are the mechanical energies);
# heat_content itself is checked with the file (it carries rho c T0 V, which
# would hide the changes), its change here.
HEAT = ("heat_content_change", "boundary_heat_in", "source_heat", "plastic_heat",
        "thermoelastic_heat", "heat_balance_error")
for f in ("reactions.csv", "probes.csv", "energy.csv"):
    try:
        a, b = read_csv(o1 + "/" + f), read_csv(o2 + "/" + f)
    except FileNotFoundError:
        continue
    if not a:
        continue
    check(sorted(a) == sorted(b), "%s: same columns" % f)
    keys = [k for k in a if k in b]
    compare(f, a, b, keys)
    # Temperatures and heat on their own scale (not hidden behind stresses or work).
    own = [k for k in keys if k.endswith("_temperature")] if f == "probes.csv" else \
          [k for k in keys if k in HEAT] if f == "energy.csv" else []
    if own:
        compare(f + " " + ("temperature columns" if f == "probes.csv" else "heat columns"), a, b, own)
for k, v in s1.get("quantities_of_interest", {}).items():
    w = s2["quantities_of_interest"][k]
    check(abs(v - w) <= 1e-8 * max(abs(v), 1e-12), "%s: %.12g (np=1) vs %.12g (np=2)" % (k, v, w))
finish()

"""np = 1 and np = 2 give the same answer: the reaction-force history of every
named boundary, the probe history and the energy history (with the heat
columns when the scene has a temperature field) agree to solver tolerance
(relative RTOL of the largest value of the file, 1e-8 unless --rtol); the
temperature columns of probes.csv and the heat columns of energy.csv are also
checked against their own scale. With a heat equation, ARKode makes the same
decisions on both: the same internal steps, attempts, error-test and
nonlinear-solver failures and Newton iterations in every step (thermal.csv).

Usage: mpi_consistency.py [scene.prm] [--rtol R] [--set 'Section/Entry=value' ...]
(default scene prm/cantilever.prm; --set overrides are passed to both runs)."""
import sys
from anvil_test import run, read_csv, check, finish

scene, extra, rtol = "prm/cantilever.prm", [], 1e-8
args = sys.argv[1:]
while args:
    a = args.pop(0)
    if a == "--rtol" and args:
        rtol = float(args.pop(0))
    elif a == "--set" and args:
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
    """Largest difference over the columns keys, relative rtol of their largest value."""
    scale = max(max(abs(x) for x in a[k]) for k in keys) or 1.0
    worst = max(abs(x - y) for k in keys for x, y in zip(a[k], b[k]))
    check(worst <= rtol * scale, "%s: np=1 vs np=2 largest difference %.3e (scale %.3e, relative %.1e <= %.0e)"
          % (what, worst, scale, worst / scale, rtol))


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
# ARKode's decisions: the same counts in every step (name before any unit).
try:
    t1, t2 = read_csv(o1 + "/thermal.csv"), read_csv(o2 + "/thermal.csv")
except FileNotFoundError:
    t1 = t2 = {}
DECISIONS = ("arkode_steps", "arkode_attempts", "error_test_failures", "nonlinear_iterations",
             "nonlinear_failures")
for k in t1:
    if k.split(" [")[0] in DECISIONS:
        differ = [i for i, (x, y) in enumerate(zip(t1[k], t2[k])) if x != y]
        check(len(t1[k]) == len(t2[k]) and not differ,
              "thermal.csv %s: the same in every step on np=1 and np=2 (%d rows%s)"
              % (k, len(t1[k]), "" if not differ else ", first differs in row %d: %g vs %g"
                 % (differ[0], t1[k][differ[0]], t2[k][differ[0]])))
for k, v in s1.get("quantities_of_interest", {}).items():
    w = s2["quantities_of_interest"][k]
    check(abs(v - w) <= rtol * max(abs(v), 1e-12), "%s: %.12g (np=1) vs %.12g (np=2)" % (k, v, w))
finish()

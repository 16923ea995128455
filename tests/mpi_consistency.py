"""np = 1 and np = 2 give the same answer: the reaction-force history of every
named boundary and the probe history of the cantilever agree to solver
tolerance (relative 1e-8 of the largest value)."""
import sys
from anvil_test import run, read_csv, check, finish

scene = sys.argv[1] if len(sys.argv) > 1 else "prm/cantilever.prm"
name = scene.replace("/", "_").replace(".prm", "")
sets = ["Output/Field interval=0", "Mechanics/Newton/Residual tolerance=1e-12"]
o1, s1, _ = run(scene, sets, np=1, name=name + "_np1")
o2, s2, _ = run(scene, sets, np=2, name=name + "_np2")
check(s2["processes"] == 2, "second run used 2 processes")
check(s1["steps"] == s2["steps"], "same number of steps (%d, %d)" % (s1["steps"], s2["steps"]))
for f in ("reactions.csv", "probes.csv"):
    try:
        a, b = read_csv(o1 + "/" + f), read_csv(o2 + "/" + f)
    except FileNotFoundError:
        continue
    scale = max(max(abs(x) for x in v) for v in a.values()) or 1.0
    worst = max(abs(x - y) for k in a for x, y in zip(a[k], b[k]))
    check(worst <= 1e-8 * scale, "%s: np=1 vs np=2 largest difference %.3e (scale %.3e)" % (f, worst, scale))
for k, v in s1.get("quantities_of_interest", {}).items():
    w = s2["quantities_of_interest"][k]
    check(abs(v - w) <= 1e-8 * max(abs(v), 1e-12), "%s: %.12g (np=1) vs %.12g (np=2)" % (k, v, w))
finish()

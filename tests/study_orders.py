"""Observed orders measured by the study tool (anvil --study) on scenes with
closed forms (tests/study/*.prm), against the orders of the methods:

 - backward Euler (the Perzyna material update) on the relaxation of a bar in
   uniaxial stress, sigma = sigma_0 + (E ln 1.005 - sigma_0) exp(-E t/eta): 1;
 - ARKode DIRK of order 2, 3, 4 with fixed steps on the slowest cosine mode of
   an insulated strip, against the semi-discrete closed form (the nodal cosine
   is an eigenvector of the Q1 mass and stiffness, so no space error enters);
 - Q1 in space on the same mode against the continuous closed form: 2.

Each within 0.1 (fitted over the ladder and over its last two runs). The
test also recomputes each run's error from the value in study.csv and its own
closed form, so the tool's error column is checked, not only its slopes.
"""
import csv
import json
import math
import os
import subprocess

from anvil_test import ANVIL, SOURCE_DIR, WORK_DIR, check, close, finish

a = 50 / (7.8e-9 * 4.6e8)


def lambda_h(dx, L=10.0):
    th = math.pi * dx / L
    return a * 6 / dx ** 2 * (1 - math.cos(th)) / (2 + math.cos(th))


closed = {"orders_backward_euler": lambda row: 300 + (200000 * math.log(1.005) - 300) * math.exp(-2.0),
          "orders_dirk": lambda row: 300 + 100 * math.exp(-lambda_h(0.5)),
          "orders_space": lambda row: 300 + 100 * math.exp(-a * (math.pi / 10) ** 2)}
expected = {"orders_backward_euler": {"all runs": 1},
            "orders_dirk": {"method=DIRK order 2": 2, "method=DIRK order 3": 3, "method=DIRK order 4": 4},
            "orders_space": {"all runs": 2}}

for name in ("orders_backward_euler", "orders_dirk", "orders_space"):
    out = os.path.join(WORK_DIR, "output", "study_" + name)
    p = subprocess.run([ANVIL, "--study", os.path.join(SOURCE_DIR, "tests", "study", name + ".prm"),
                        "--output", out], capture_output=True, text=True)
    print(p.stdout.strip().split("\n")[-1])
    check(p.returncode == 0, "%s: anvil --study exits with 0 (%d) %s" % (name, p.returncode, p.stderr.strip()))
    with open(os.path.join(out, "study.csv")) as f:
        rows = list(csv.DictReader(f))
    qname = [k for k in rows[0] if k.startswith("error_")][0][6:]
    worst = 0.0
    for r in rows:
        mine = abs(float(r[qname]) - closed[name](r))
        worst = max(worst, abs(mine - float(r["error_" + qname])) / mine)
    check(worst < 1e-9, "%s: the tool's errors equal |value - closed form| recomputed here (worst relative "
          "difference %.2g)" % (name, worst))
    with open(os.path.join(out, "orders.json")) as f:
        orders = [o for o in json.load(f) if o["quantity"] == qname]
    for group, order in expected[name].items():
        o = next(o for o in orders if o["group"] == group)
        print("  %s, %s: errors %s" % (name, group, " ".join("%.3e" % e for e in o["e"])))
        close(o["order_fit"], order, 0, "%s, %s: fitted order" % (name, group), atol=0.1)
        close(o["order_last"], order, 0, "%s, %s: order of the last two runs" % (name, group), atol=0.1)
finish()

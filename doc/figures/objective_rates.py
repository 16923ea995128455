#!/usr/bin/python3
"""Makes doc/figures/objective_rates.png: simple shear of a hypoelastic point
to gamma = 8 with the three objective rates (anvil --material-point,
prm/material_point/simple_shear.prm, 800 steps) over their closed forms
(tests/objective_rates.py lists them).

    /usr/bin/python3 doc/figures/objective_rates.py [path/to/anvil]"""
import csv
import math
import os
import subprocess
import sys
import tempfile

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt

here = os.path.dirname(os.path.abspath(__file__))
source = os.path.dirname(os.path.dirname(here))
anvil = sys.argv[1] if len(sys.argv) > 1 else os.path.join(source, "build", "anvil")
E, nu, gamma = 200000.0, 0.3, 8.0
G = E / (2 * (1 + nu))


def closed_form(rate, g):
    if rate == "Jaumann":
        return G * math.sin(g), G * (1 - math.cos(g))
    if rate == "Green-Naghdi":  # Dienes (1979), tan(beta) = gamma/2
        b = math.atan(g / 2)
        return (2 * G * math.cos(2 * b) * (2 * b - 2 * math.tan(2 * b) * math.log(math.cos(b)) - math.tan(b)),
                4 * G * (math.cos(2 * b) * math.log(math.cos(b)) + b * math.sin(2 * b) - math.sin(b) ** 2))
    lam, r = g / 2 + math.sqrt(1 + g * g / 4), math.sqrt(1 + g * g / 4)  # Hencky, 2G ln V
    return 2 * G * math.log(lam) / r, G * g * math.log(lam) / r


def run(rate, work):
    out = os.path.join(work, rate + ".csv")
    subprocess.run([anvil, "--material-point", os.path.join(source, "prm", "material_point", "simple_shear.prm"),
                    "--set", "Path/Objective rate=" + rate, "--set", "Path/Deformation gradient=F12: %g*t" % gamma,
                    "--set", "Path/Steps=800", "--set", "Output/File=" + out], check=True, capture_output=True)
    with open(out) as f:
        rows = list(csv.DictReader(f))
    key = lambda row, name: next(v for k, v in row.items() if k.split(" [")[0] == name)
    t = [float(key(r, "time")) for r in rows]
    return ([gamma * x for x in t], [float(key(r, "sxy")) / G for r in rows],
            [float(key(r, "sxx")) / G for r in rows])


fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(10, 4.2))
g = [8.0 * i / 400 for i in range(401)]
with tempfile.TemporaryDirectory() as work:
    for rate, colour in (("Jaumann", "C0"), ("Green-Naghdi", "C1"), ("logarithmic", "C2")):
        gg, sxy, sxx = run(rate, work)
        exact = [closed_form(rate, x) for x in g]
        label = rate + (" (Hencky)" if rate == "logarithmic" else "")
        ax1.plot(g, [e[0] / G for e in exact], "-", color=colour, label=label + ", closed form")
        ax2.plot(g, [e[1] / G for e in exact], "-", color=colour, label=label + ", closed form")
        ax1.plot(gg[::40], sxy[::40], "o", color=colour, mfc="none", label=label + ", anvil")
        ax2.plot(gg[::40], sxx[::40], "o", color=colour, mfc="none", label=label + ", anvil")
ax1.axvline(math.pi / 2, color="grey", lw=0.8, ls=":")
ax1.text(math.pi / 2 + 0.1, -0.9, "γ = π/2", color="grey")
ax1.set_xlabel("shear γ [-]")
ax1.set_ylabel("σ_xy / G [-]")
ax2.set_xlabel("shear γ [-]")
ax2.set_ylabel("σ_xx / G = −σ_yy / G [-]")
ax1.set_title("shear stress")
ax2.set_title("normal stress")
ax1.legend(fontsize=7, loc="upper left")
for ax in (ax1, ax2):
    ax.grid(alpha=0.3)
fig.suptitle("Simple shear of a hypoelastic body: the three objective rates")
fig.tight_layout()
fig.savefig(os.path.join(here, "objective_rates.png"), dpi=110)
print("wrote", os.path.join(here, "objective_rates.png"))

"""The coupling schemes side by side (prints figures, asserts nothing; issue 11):
on the thermal necking bar (prm/necking_bar_thermal.prm) and the two-block
scene (prm/two_blocks.prm), per scheme (isothermal split, adiabatic split,
iterated staggered, monolithic): wall time, steps, Newton and linear
iterations, and the error of the end force, the neck temperature and the neck
radius (necking bar) or both temperature rises and the friction work (two
blocks) against the tightest monolithic run at the same time steps.

    contrib/bench/monolithic.py [--small] [--time-step DT]
Environment: ANVIL_EXECUTABLE (default build/anvil), ANVIL_BENCH_DIR."""
import json
import os
import subprocess
import sys
import time

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
ANVIL = os.environ.get("ANVIL_EXECUTABLE", os.path.join(ROOT, "build", "anvil"))
OUT = os.environ.get("ANVIL_BENCH_DIR", os.path.join(ROOT, "build", "bench"))
small = "--small" in sys.argv
dt = sys.argv[sys.argv.index("--time-step") + 1] if "--time-step" in sys.argv else "0.1"
env = dict(os.environ, DEAL_II_NUM_THREADS="1", OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")


def run(scene, name, sets):
    out = os.path.join(OUT, "monolithic_" + name)
    cmd = [ANVIL, os.path.join(ROOT, scene), "--set", "Output/Directory=" + out, "--set", "Output/Field interval=0",
           "--set", "Output/Verbosity=quiet"]
    for s in sets:
        cmd += ["--set", s]
    start = time.time()
    p = subprocess.run(cmd, capture_output=True, text=True, env=env)
    wall = time.time() - start
    if p.returncode != 0:
        return None, (p.stdout + p.stderr).strip().splitlines()[-1:] or ["status %d" % p.returncode]
    return json.load(open(os.path.join(out, "summary.json"))), wall


schemes = ["isothermal split", "adiabatic split", "iterated staggered", "monolithic"]
bar = ["Time/Time step=" + dt, "Time/Growth factor=1"]
if small:
    bar += ["Geometry/Radial cells=5", "Geometry/Axial cells=20"]
# The reference: the tightest monolithic run each scene reaches. On two_blocks
# the first touch and the release leave a residual floor of ~1e-11 N at a
# force scale of ~1e-2 N: 1e-10 relative with 1e-9 N absolute.
scenes = [("prm/necking_bar_thermal.prm", "necking_bar", bar,
           ["final_force", "neck_centre_temperature", "neck_radius_change"],
           ["Physics/Monolithic tolerance=1e-12"]),
          ("prm/two_blocks.prm", "two_blocks", [], ["delta_T_upper", "delta_T_lower", "friction_work"],
           ["Physics/Monolithic tolerance=1e-10", "Mechanics/Newton/Absolute residual tolerance=1e-9"])]
for scene, tag, sets, qois, tight in scenes:
    ref, _ = run(scene, tag + "_reference", sets + ["Physics/Coupling=monolithic"] + tight)
    print("%s (%s), one process, one thread:" % (scene, " ".join(sets) or "as shipped"))
    print("  %-19s %7s %6s %7s %7s %7s  %s" % ("scheme", "wall s", "steps", "Newton", "linear", "cuts",
                                             "  ".join("err %s" % q for q in qois)))
    for scheme in schemes:
        s, wall = run(scene, tag + "_" + scheme.split()[0], sets + ["Physics/Coupling=" + scheme])
        if s is None:
            print("  %-19s failed: %s" % (scheme, wall[0]))
            continue
        q = s.get("quantities_of_interest", {})
        errors = []
        for k in qois:
            if ref is None or k not in q:
                errors.append("%*s" % (len(k) + 4, "-"))
            else:
                r = ref["quantities_of_interest"][k]
                errors.append("%*.2e" % (len(k) + 4, abs(q[k] - r) / max(abs(r), 1e-300)))
        print("  %-19s %7.2f %6d %7d %7d %7d  %s" % (scheme, wall, s["steps"], s["newton_iterations"],
                                                   s.get("linear_iterations", 0), s["cut_backs"], "  ".join(errors)))
    if ref is None:
        print("  (no monolithic reference: the scene is not supported by it)")
print("errors: relative, against the tightest monolithic run at the same steps; "
      "Newton: the monolithic and the mechanical iterations (iterated staggered: over all its mechanics solves)")

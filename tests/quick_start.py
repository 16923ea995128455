"""contrib/run.sh without an argument: the seed's two-block scene (Ponthot &
Adam, section 4.2; prm/two_blocks.prm), its table and its figures.

The printed dT_upper / dT_lower are checked against the energy balance
(friction work mu p w s, half into each block, spread over rho c V:
1.2346 / 0.3086 K) to 0.5 %, and the seed's values must be printed beside
them; the scene's figures must be written and non-empty. Runs in a scratch
directory with the build of this tree (ANVIL_SKIP_BUILD: ctest built it).
"""
import os
import re
import subprocess

from anvil_test import ANVIL, SOURCE_DIR, WORK_DIR, check, close, finish

work = os.path.join(WORK_DIR, "output", "quick_start")
os.makedirs(work, exist_ok=True)
env = dict(os.environ, ANVIL_BUILD=os.path.dirname(os.path.abspath(ANVIL)), ANVIL_SKIP_BUILD="1",
           DEAL_II_NUM_THREADS="1")
p = subprocess.run([os.path.join(SOURCE_DIR, "contrib", "run.sh")], cwd=work, env=env,
                   capture_output=True, text=True)
print(p.stdout[-1600:])
if p.returncode != 0:
    print(p.stderr[-3000:])
check(p.returncode == 0, "contrib/run.sh exits 0")

rho_c, W = 2.7e-9 * 0.9e9, 0.2 * 10 * 1.25 * 3.75
for block, volume, seed in (("upper", 1.25 * 1.25, "1.231"), ("lower", 5 * 1.25, "0.307")):
    m = re.search(r"dT_%s\s+(\S+)\s+(\S+)\s+(\S+)" % block, p.stdout)
    check(m is not None, "dT_%s printed" % block)
    if m:
        close(float(m.group(1)), W / 2 / (rho_c * volume), 5e-3, "dT_%s (K) vs the energy balance" % block)
        close(float(m.group(2)), W / 2 / (rho_c * volume), 2e-4, "the balance value printed beside it")
        check(m.group(3) == seed, "the seed's value %s printed beside it" % seed)

figures = os.path.join(work, "output", "two_blocks", "figures")
names = sorted(os.listdir(figures)) if os.path.isdir(figures) else []
print("  figures: " + ", ".join(names))
check(len(names) >= 4 and all(os.path.getsize(os.path.join(figures, n)) > 10000 for n in names),
      "the scene's figures are written and non-empty (%d)" % len(names))
check("results in output/two_blocks:" in p.stdout, "the last line says where the results are")
finish()

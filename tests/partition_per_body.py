"""Geometry/Partition = per body (issue 15): every process holds a share of
every body, and the answer does not depend on it.

 1. two_blocks (frictional heating contact, 2 bodies) on 2 processes with the
    per-body partition ends with the answer of 1 process with p4est's
    partition: reactions, probes, energies and quantities of interest to solver
    tolerance (1e-8 of each file's largest value), the same steps.
 2. The contact strip (contrib/bench/contact_strip.prm, 100 cells along the
    upper strip, GMRES + AMG at 1e-10) the same way.
 3. A restart with the per-body partition: two_blocks stopped half way and
    resumed ends with the uninterrupted run's answer (1e-9), on 1 process and
    on 2 (where deal.II 9.4's load read process 1's cell data from process
    0's place: include/anvil/geometry/partition.h); plastic_block (J2, its
    points' states on both processes) stopped at t = 0.5 and resumed on 2
    processes ends with the uninterrupted 2-process run's reactions (1e-9).
    On another process count, on another mesh (the checkpoint holds none: the
    scene's is checked against it), or from p4est's checkpoint, the restart
    is refused with one line naming Output/Restart from (exit 2).
 4. A bad Geometry/Partition is one error line naming the entry (exit 2)."""
import os
import subprocess
from anvil_test import ANVIL, SOURCE_DIR, run, check, close, finish, histories_agree

quiet = ["Output/Field interval=0", "Output/Verbosity=quiet", "Mechanics/Newton/Residual tolerance=1e-12"]
per_body = ["Geometry/Partition=per body"]
short = ["Time/End time=1e-3"]

o1, s1, _ = run("prm/two_blocks.prm", quiet + short, name="part_two_blocks_np1")
o2, s2, _ = run("prm/two_blocks.prm", quiet + short + per_body, np=2, name="part_two_blocks_np2")
check(s2["processes"] == 2 and s1["steps"] == s2["steps"],
      "two_blocks: np 2 per body took the steps of np 1 (%d, %d)" % (s1["steps"], s2["steps"]))
histories_agree(o1, o2, ["reactions.csv", "energy.csv"], 1e-8, "two_blocks np 1 (p4est) vs np 2 (per body)")
for k, v in s1["quantities_of_interest"].items():
    close(s2["quantities_of_interest"][k], v, 1e-8, "two_blocks np 2 per body: " + k, atol=1e-12)
tb_out2, tb_s2 = o2, s2

n = 100
strip = ["Geometry/Blocks=lower: 0, 0, 1, 0.02, %d, 2; upper: 0, 0.02, 1, 0.04, %d, 2" % (n - 1, n),
         "Boundary conditions/Displacement=lower.bottom: ux = 0, uy = 0; upper.left: ux = 0",
         "Mechanics/Linear solver/Type=iterative", "Mechanics/Linear solver/Tolerance=1e-10"]
o1, s1, _ = run("contrib/bench/contact_strip.prm", quiet + strip, name="part_strip_np1")
o2, s2, _ = run("contrib/bench/contact_strip.prm", quiet + strip + per_body, np=2, name="part_strip_np2")
check(s1["steps"] == s2["steps"] and s1["newton_iterations"] == s2["newton_iterations"],
      "strip: the same steps and Newton iterations (%d, %d)" % (s1["newton_iterations"], s2["newton_iterations"]))
histories_agree(o1, o2, ["reactions.csv", "energy.csv"], 1e-8, "strip np 1 (p4est) vs np 2 (per body)")

half = ["Time/End time=5e-4"]
out_full, full, _ = run("prm/two_blocks.prm", quiet + short + per_body, name="part_full")
out_half, _, _ = run("prm/two_blocks.prm", quiet + half + per_body, name="part_half")
_, resumed, _ = run("prm/two_blocks.prm", quiet + short + per_body + ["Output/Restart from=" + out_half + "/checkpoint"],
                    name="part_half")
check(resumed["steps"] == full["steps"], "resumed: %d steps in all, as the full run" % resumed["steps"])
for k, v in full["quantities_of_interest"].items():
    close(resumed["quantities_of_interest"][k], v, 1e-9, "per body, resumed on 1 process: " + k, atol=1e-14)
histories_agree(out_full, out_half, ["reactions.csv"], 1e-9, "per body resumed vs uninterrupted")
out_half2, _, _ = run("prm/two_blocks.prm", quiet + half + per_body, np=2, name="part_half2")
_, resumed2, _ = run("prm/two_blocks.prm", quiet + short + per_body + ["Output/Restart from=" + out_half2 + "/checkpoint"],
                     np=2, name="part_half2")
check(resumed2["steps"] == tb_s2["steps"], "resumed on 2: %d steps in all, as the full run" % resumed2["steps"])
for k, v in tb_s2["quantities_of_interest"].items():
    close(resumed2["quantities_of_interest"][k], v, 1e-9, "per body, resumed on 2 processes: " + k, atol=1e-14)
histories_agree(tb_out2, out_half2, ["reactions.csv", "energy.csv"], 1e-9, "per body np 2 resumed vs uninterrupted")

block = ["Geometry/Partition=per body", "Output/Quantities of interest=Fy: reaction(bottom, y); Fx: reaction(bottom, x)"]
ob, sb, _ = run("tests/plastic_block.prm", block, np=2, name="part_block_full")
oh, _, _ = run("tests/plastic_block.prm", block + ["Time/End time=0.5"], np=2, name="part_block_half")
_, rb, _ = run("tests/plastic_block.prm", block + ["Output/Restart from=" + oh + "/checkpoint"], np=2, name="part_block_half")
for k, v in sb["quantities_of_interest"].items():
    close(rb["quantities_of_interest"][k], v, 1e-9, "plastic_block per body, resumed on 2 processes: " + k)
histories_agree(ob, oh, ["reactions.csv"], 1e-9, "plastic_block per body np 2 resumed vs uninterrupted")


def one_line(sets, np, expected, what):
    cmd = [ANVIL, os.path.join(SOURCE_DIR, "prm/two_blocks.prm")]
    for x in sets:
        cmd += ["--set", x]
    if np > 1:
        cmd = ["mpirun", "-np", str(np), "--oversubscribe"] + cmd
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    p = subprocess.run(cmd, capture_output=True, text=True, env=env)
    # anvil's own lines (mpirun adds its banner about the exit code).
    lines = [x for x in p.stderr.strip().splitlines() if x.startswith("anvil")]
    check(p.returncode == 2 and len(lines) == 1 and all(e in lines[0] for e in expected),
          "%s: exit %d, %r" % (what, p.returncode, lines))


one_line(quiet + per_body + ["Output/Restart from=" + out_half2 + "/checkpoint", "Output/Directory=" + out_half2 + "_r1"],
         1, ["Output/Restart from", "per body", "2 processes"], "2 processes' per-body checkpoint resumed on 1")
# A per-body checkpoint holds no mesh: the restart recreates it from the scene
# and refuses one that is not the saved one (same cells, other vertices).
one_line(quiet + per_body + ["Output/Restart from=" + out_half2 + "/checkpoint",
                             "Output/Directory=" + out_half2 + "_moved",
                             "Geometry/Blocks=lower: 0, 0, 5, 1.3, 30, 10; upper: 0, 1.3, 1.25, 2.5, 10, 10"],
         2, ["Output/Restart from", "mesh", "Geometry"], "per-body checkpoint resumed on another mesh")
out_p4est, _, _ = run("prm/two_blocks.prm", quiet + half, name="part_p4est_half")
one_line(quiet + per_body + ["Output/Restart from=" + out_p4est + "/checkpoint",
                             "Output/Directory=" + out_p4est + "_pb"], 1,
         ["Output/Restart from", "Geometry/Partition"], "p4est's checkpoint resumed per body")
one_line(["Geometry/Partition=metis"], 1, ["Geometry/Partition", "metis"], "Geometry/Partition = metis")
finish()

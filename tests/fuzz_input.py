"""Hostile input cannot fool anvil: seeded mutations of the shipped scenes.

Every shipped scene (prm/*.prm) is mutated the way a careless or hostile user
would (values replaced by hostile ones, entries misspelled, lines deleted or
repeated, the file truncated or filled with garbage, gmsh meshes corrupted) and
run with --check; a few mutations of material and load values are run for two
steps. The promise checked for every case (issue 17):

  - the exit status is 0, 2 or 3: never a signal, never a hang (timeout);
  - exit 2 prints one line, "anvil: error: ...", naming the file (the scene,
    its mesh, or --set) and the parameter (a quoted entry or file:line);
  - no deal.II banner (TimerOutput's table, "An error occurred in line").

The counts per mutation and per outcome are printed at the end.
Usage: fuzz_input.py [N_CHECK] [N_RUN] [SEED]  (defaults 240, 8, 17).
"""
import concurrent.futures
import os
import random
import re
import shutil
import subprocess
import sys
import tempfile
import time
from collections import Counter, defaultdict

from anvil_test import ANVIL, SOURCE_DIR, WORK_DIR, check, finish

N_CHECK = int(sys.argv[1]) if len(sys.argv) > 1 else 240
N_RUN = int(sys.argv[2]) if len(sys.argv) > 2 else 8
SEED = int(sys.argv[3]) if len(sys.argv) > 3 else 17
CHECK_TIMEOUT, RUN_TIMEOUT = 60, 180
rng = random.Random(SEED)

PRM = os.path.join(SOURCE_DIR, "prm")
SCENES = sorted(f for f in os.listdir(PRM) if f.endswith(".prm"))
SET_RE = re.compile(r"^(\s*set\s+)([^=]+?)(\s*=\s*)(.*)$")

HOSTILE_VALUES = ["", "-1", "0", "-0", "1e308", "-1e308", "1e-308", "nan", "inf", "-inf", "1/0",
                  "sqrt(-1)", "abc", "1,2,3", ":", ";", "((", "70000", "4294967296", "-2147483649",
                  "0x10", "1e", "9" * 100000, "A" * 100000, "1." + "0" * 5000 + "1", "\x00\x01",
                  "t/0", "log(t-1)", "1e300*1e300", "left: ux = 1/0", "tip: 1e9, 1e9",
                  "tip: 0, 0; tip: 0, 0", "/proc/anvil_cannot/x", "x" * 5000]


def numbers_scaled(value):
    """The value's numbers scaled, negated or zeroed (plausible-looking mistakes)."""
    def repl(m):
        x = float(m.group(0))
        return repr(rng.choice([-x, 0.0, x * 1e6, x * 1e-6, x * 1e300, x + 1e-300, -1e-3]))
    return re.sub(r"(?<![A-Za-z_])[-+]?\d+\.?\d*(?:[eE][-+]?\d+)?", repl, value, count=1)


def mutate_scene(lines):
    """One mutation of a scene's lines: (category, new lines)."""
    sets = [i for i, l in enumerate(lines) if SET_RE.match(l)]
    kind = rng.choice(["hostile value", "hostile value", "hostile value", "scaled number",
                       "scaled number", "misspelled entry", "long entry name", "deleted line",
                       "repeated line", "truncated file", "garbage bytes", "swapped values"])
    lines = list(lines)
    i = rng.choice(sets)
    head, entry, eq, value = SET_RE.match(lines[i]).groups()
    if kind == "hostile value":
        lines[i] = head + entry + eq + rng.choice(HOSTILE_VALUES)
    elif kind == "scaled number":
        if not re.search(r"\d", value):
            value = "1"
        lines[i] = head + entry + eq + numbers_scaled(value)
    elif kind == "misspelled entry":
        k = rng.randrange(len(entry))
        lines[i] = head + entry[:k] + entry[k + 1:] + eq + value
    elif kind == "long entry name":
        lines[i] = head + entry + "x" * 100000 + eq + value
    elif kind == "deleted line":
        del lines[rng.randrange(len(lines))]
    elif kind == "repeated line":
        k = rng.randrange(len(lines))
        lines.insert(k, lines[k])
    elif kind == "truncated file":
        text = "\n".join(lines)
        return kind, text[:rng.randrange(len(text))].split("\n")
    elif kind == "garbage bytes":
        k = rng.randrange(len(lines))
        lines.insert(k, "".join(chr(rng.randrange(1, 256)) for _ in range(rng.randrange(1, 200))))
    elif kind == "swapped values":
        j = rng.choice(sets)
        vj = SET_RE.match(lines[j]).group(4)
        lines[i], lines[j] = head + entry + eq + vj, SET_RE.match(lines[j]).group(1) + \
            SET_RE.match(lines[j]).group(2) + SET_RE.match(lines[j]).group(3) + value
    return kind, lines


def mutate_mesh(text):
    """One corruption of a gmsh 2.2 file: (category, new text)."""
    lines = text.split("\n")
    n0 = lines.index("$Nodes") + 2
    e0 = lines.index("$Elements") + 2
    kind = rng.choice(["mesh: truncated", "mesh: NaN coordinate", "mesh: missing node",
                       "mesh: wrong node count", "mesh: wrong element count",
                       "mesh: repeated node in a quad", "mesh: unknown node in an element",
                       "mesh: huge count", "mesh: garbage line"])
    if kind == "mesh: truncated":
        return kind, text[:rng.randrange(len(text) // 3, len(text))]
    if kind == "mesh: NaN coordinate":
        k = rng.randrange(n0, lines.index("$EndNodes"))
        f = lines[k].split()
        f[rng.randrange(1, 3)] = rng.choice(["nan", "inf", "1e999", "-nan"])
        lines[k] = " ".join(f)
    elif kind == "mesh: missing node":
        del lines[rng.randrange(n0, lines.index("$EndNodes"))]
    elif kind == "mesh: wrong node count":
        lines[n0 - 1] = str(int(lines[n0 - 1]) + rng.choice([-3, -1, 1, 7]))
    elif kind == "mesh: wrong element count":
        lines[e0 - 1] = str(int(lines[e0 - 1]) + rng.choice([-3, -1, 1, 7]))
    elif kind == "mesh: huge count":
        k = rng.choice([n0 - 1, e0 - 1])
        lines[k] = rng.choice(["99999999999", "-5", "4294967297", "1e9"])
    elif kind == "mesh: garbage line":
        lines.insert(rng.randrange(n0, len(lines)), "x%$ 1 2 garbage")
    else:
        quads = [k for k in range(e0, lines.index("$EndElements")) if lines[k].split()[1] == "3"]
        k = rng.choice(quads)
        f = lines[k].split()
        if kind == "mesh: repeated node in a quad":
            f[-1] = f[-3]
        else:
            f[-1] = "999999"
        lines[k] = " ".join(f)
    return kind, "\n".join(lines)


def run_case(case):
    """Run one case; returns (category, outcome, problem or None, command text)."""
    kind, scene_file, extra, timeout, workdir = case
    cmd = [ANVIL, scene_file, "--set", "Output/Directory=" + os.path.join(workdir, "out"),
           "--set", "Output/Verbosity=quiet"] + extra
    env = dict(os.environ, DEAL_II_NUM_THREADS="1", OMPI_ALLOW_RUN_AS_ROOT="1",
               OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    try:
        p = subprocess.run(cmd, capture_output=True, timeout=timeout, cwd=workdir, env=env)
    except subprocess.TimeoutExpired:
        return kind, "hang", "no answer within %d s" % timeout
    out = p.stdout.decode(errors="replace")
    err = p.stderr.decode(errors="replace")
    rc = p.returncode
    if rc < 0:
        return kind, "signal", "killed by signal %d: %s" % (-rc, err[-300:])
    if rc not in (0, 2, 3):
        return kind, "exit %d" % rc, err[-300:]
    for banner in ("An error occurred in line", "+---------", "Total wallclock time"):
        if banner in out + err and rc != 0:
            return kind, "banner", "deal.II banner %r in the output" % banner
    if rc == 2:
        lines = [l for l in err.split("\n") if l.strip()]
        if len(lines) != 1 or not lines[0].startswith("anvil: error: "):
            return kind, "exit 2", "%d lines: %r" % (len(lines), err[:300])
        msg = lines[0]
        names = [os.path.basename(scene_file), "--set"] + \
            [os.path.basename(e.split("=", 1)[1]) for e in extra if e.startswith("Geometry/Mesh file=")]
        if not any(n in msg for n in names):
            return kind, "exit 2", "does not name the file: %r" % msg[:300]
        if not ("'" in msg or re.search(r":\d+:", msg)):
            return kind, "exit 2", "does not name the parameter: %r" % msg[:300]
        if len(msg) > 2000:
            return kind, "exit 2", "a %d-character line" % len(msg)
    return kind, "exit %d" % rc, None


def build_cases(root):
    cases = []
    meshes = {s: open(os.path.join(PRM, s)).read() for s in SCENES}
    gmsh_scenes = [s for s in SCENES if "Mesh file" in meshes[s]]
    for n in range(N_CHECK + N_RUN):
        d = os.path.join(root, "case%04d" % n)
        os.makedirs(d)
        scene = rng.choice(SCENES)
        lines = meshes[scene].split("\n")
        extra = []
        if n < N_CHECK and rng.random() < 0.15 and gmsh_scenes:
            scene = rng.choice(gmsh_scenes)
            lines = meshes[scene].split("\n")
            mesh = re.search(r"set Mesh file\s*=\s*(\S+)", meshes[scene]).group(1)
            kind, text = mutate_mesh(open(os.path.join(PRM, mesh)).read())
            open(os.path.join(d, "mutated.msh"), "w").write(text)
            extra = ["Geometry/Mesh file=" + os.path.join(d, "mutated.msh")]
        elif n < N_CHECK:
            kind, lines = mutate_scene(lines)
        else:
            # A short real run: a material, load or contact value made hostile.
            scene = rng.choice(["cantilever.prm", "two_blocks.prm", "necking_bar_thermal.prm",
                                "heat_half_space.prm", "thick_cylinder.prm", "bimaterial_gmsh.prm"])
            lines = meshes[scene].split("\n")
            sets = [i for i, l in enumerate(lines) if SET_RE.match(l) and not re.search(
                r"Time|Output|Directory|Restart|Dimension|Names|Pairs|Tools|Mesh file|refinements|Blocks|Cells",
                l)]
            i = rng.choice(sets)
            head, entry, eq, value = SET_RE.match(lines[i]).groups()
            lines[i] = head + entry + eq + rng.choice([numbers_scaled(value) if re.search(r"\d", value)
                                                       else value, rng.choice(HOSTILE_VALUES[:20])])
            kind = "run: " + entry.strip()
            step = re.search(r"set Time step\s*=\s*(\S+)", meshes[scene]).group(1)
            extra = ["Time/End time=%r" % (2 * float(step)), "Output/Field interval=0"]
            # A heat capacity scaled by 1e-6 makes ARKode take its 5000 steps
            # in every attempt of the cut-back cascade (minutes, not a hang):
            # fewer per attempt keep the run inside the timeout.
            if "subsection Heat" in meshes[scene]:
                extra.append("Heat/Time integration/Maximum internal steps=300")
        path = os.path.join(d, scene)
        with open(path, "w", errors="surrogateescape") as f:
            f.write("\n".join(lines))
        for m in ("meshes",):
            if not os.path.exists(os.path.join(d, m)):
                os.symlink(os.path.join(PRM, m), os.path.join(d, m))
        cases.append((kind, path, ["--check"] if n < N_CHECK else [],
                      CHECK_TIMEOUT if n < N_CHECK else RUN_TIMEOUT, d))
        cases[-1] = (kind, path, sum([["--set", e] for e in extra], []) + cases[-1][2],
                     cases[-1][3], d)
    return cases


root = tempfile.mkdtemp(prefix="fuzz_", dir=WORK_DIR)
cases = build_cases(root)
start = time.time()
with concurrent.futures.ThreadPoolExecutor(max_workers=2) as pool:
    results = list(pool.map(run_case, cases))
by_kind = defaultdict(Counter)
outcomes = Counter()
problems = []
for (kind, path, extra, _, _), (k, outcome, problem) in zip(cases, results):
    group = "run (two steps)" if kind.startswith("run: ") else kind
    by_kind[group][outcome if problem is None else "FAIL " + outcome] += 1
    outcomes[outcome if problem is None else "FAIL " + outcome] += 1
    if problem:
        problems.append("%s: %s %s -> %s" % (kind, os.path.relpath(path, root), " ".join(
            e[:80] for e in extra), problem))
print("fuzzing: %d mutated scenes (seed %d, %d with --check, %d short runs) in %.0f s" %
      (len(cases), SEED, N_CHECK, N_RUN, time.time() - start))
for kind in sorted(by_kind):
    print("  %-34s %s" % (kind, ", ".join("%s: %d" % kv for kv in sorted(by_kind[kind].items()))))
print("  total: " + ", ".join("%s: %d" % kv for kv in sorted(outcomes.items())))
for p in problems:
    print("  " + p[:600])
check(not problems, "every mutated scene ends in exit 0, 2 or 3 as promised (%d problems)" % len(problems))
if not problems:
    shutil.rmtree(root, ignore_errors=True)
finish()

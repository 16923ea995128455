"""Helpers for anvil's scene tests: run the program, read what it wrote.

Every test derives its expected values independently of anvil (closed forms,
convergence orders, energy balances); this module only runs and reads.
"""
import csv
import json
import os
import re
import subprocess
import sys

ANVIL = os.environ.get("ANVIL_EXECUTABLE", "anvil")
SOURCE_DIR = os.environ.get("ANVIL_SOURCE_DIR", os.path.join(os.path.dirname(__file__), ".."))
WORK_DIR = os.environ.get("ANVIL_TEST_WORK_DIR", os.getcwd())
failures = []


def run(scene, sets=(), np=1, name=None, expect_status=0):
    """Run anvil on scene (a path relative to the source tree or absolute) with
    --set overrides; returns (output directory, summary dict, stdout)."""
    if not os.path.isabs(scene):
        scene = os.path.join(SOURCE_DIR, scene)
    name = name or os.path.splitext(os.path.basename(scene))[0]
    out = os.path.join(WORK_DIR, "output", name)
    cmd = [ANVIL, scene, "--set", "Output/Directory=" + out]
    for s in sets:
        cmd += ["--set", s]
    if np > 1:
        cmd = ["mpirun", "-np", str(np), "--oversubscribe"] + cmd
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
               DEAL_II_NUM_THREADS="1")
    p = subprocess.run(cmd, capture_output=True, text=True, env=env)
    if p.returncode != expect_status:
        print(p.stdout)
        print(p.stderr)
        raise SystemExit("anvil exited with %d (expected %d): %s" % (p.returncode, expect_status, " ".join(cmd)))
    summary = {}
    if os.path.exists(os.path.join(out, "summary.json")):
        with open(os.path.join(out, "summary.json")) as f:
            summary = json.load(f)
    return out, summary, p.stdout


POINT_OUT = os.path.join(WORK_DIR, "output", "material_point")


def run_point(prm, sets=(), name=None, expect_status=0, extra=()):
    """Run anvil --material-point on prm with --set overrides, the CSV going
    to output/material_point/<name>.csv; returns (csv path, stdout, stderr)."""
    name = name or os.path.splitext(os.path.basename(prm))[0]
    os.makedirs(POINT_OUT, exist_ok=True)
    csv_path = os.path.join(POINT_OUT, name + ".csv")
    if os.path.exists(csv_path):
        os.remove(csv_path)
    cmd = [ANVIL, "--material-point", prm, "--set", "Output/File=" + csv_path]
    for s in sets:
        cmd += ["--set", s]
    cmd += list(extra)
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
               DEAL_II_NUM_THREADS="1")
    p = subprocess.run(cmd, capture_output=True, text=True, env=env, cwd=POINT_OUT)
    if p.returncode != expect_status:
        print(p.stdout)
        print(p.stderr)
        raise SystemExit("anvil exited with %d (expected %d): %s" % (p.returncode, expect_status, " ".join(cmd)))
    return csv_path, p.stdout, p.stderr



def bare(name):
    """'reaction_x [N]' -> 'reaction_x': a column's name without its unit."""
    return name.split(" [", 1)[0].strip()


class Columns(dict):
    """A CSV file's columns by name; a name matches with or without its
    ' [unit]' (c["time"] and c["time [s]"] are the same column); units[name]
    is the unit of each ('' when the header has none)."""

    def __init__(self, items, units):
        super().__init__(items)
        self.units = units

    def __getitem__(self, key):
        return super().__getitem__(bare(key))

    def __contains__(self, key):
        return super().__contains__(bare(key))

    def get(self, key, default=None):
        return super().get(bare(key), default)


def read_csv(path):
    """Columns of a CSV file as a dict of float lists, by name (see Columns)."""
    with open(path) as f:
        rows = list(csv.reader(f))
    if len(rows) < 2:
        return Columns({}, {})
    header = rows[0]
    units = {bare(h): (h.split(" [", 1)[1].rstrip("]") if " [" in h else "") for h in header}
    return Columns({bare(h): [float(r[i]) for r in rows[1:]] for i, h in enumerate(header)}, units)


def check(condition, message):
    """Print a PASS/FAIL line; remember failures."""
    print(("PASS  " if condition else "FAIL  ") + message)
    if not condition:
        failures.append(message)


def close(value, expected, rtol, what, atol=0.0):
    err = abs(value - expected)
    ok = err <= rtol * abs(expected) + atol
    check(ok, "%s = %.10g, expected %.10g (error %.3g, tolerance %.3g)"
          % (what, value, expected, err, rtol * abs(expected) + atol))
    return err


def finish():
    if failures:
        print("%d check(s) failed" % len(failures))
        sys.exit(1)
    print("all checks passed")


def pattern_checks(name, summary, stdout, min_patterns=1):
    """The ANVIL_PATTERN_CHECK lines of a run (the matrix graph built both by
    anvil and by deal.II's route, compared): checks that every pattern the
    run built (summary.json's pattern_rebuilds) was compared equal; returns
    the (rows, entries) of each comparison."""
    compared = [(int(r), int(e)) for r, e in re.findall(
        r"ANVIL_PATTERN_CHECK: (\d+) rows, (\d+) entries, equal to deal.II's", stdout)]
    patterns = summary["contact"]["pattern_rebuilds"]  # the first one included
    print("  %s: %d patterns, %d compared equal (%d rows, %d to %d entries)"
          % (name, patterns, len(compared), compared[0][0] if compared else 0,
             min(e for _, e in compared) if compared else 0, max(e for _, e in compared) if compared else 0))
    check(len(compared) == patterns and patterns >= min_patterns,
          name + ": every pattern (%d) built both ways and equal" % patterns)
    return compared


def largest_column_difference(out_a, out_b, names, summary_a=None, summary_b=None):
    """The largest difference between two runs' CSV columns (files @p names in
    the output directories), each relative to its column's scale floored at
    1e-6 of its file's largest value (balance errors are round-off), and
    between their summaries' quantities of interest if given; returns
    (difference, "file column")."""
    def columns(path):
        with open(path) as f:
            rows = list(csv.reader(f))
        return {h.split(" [")[0]: [float(r[i]) for r in rows[1:]] for i, h in enumerate(rows[0])}
    worst, where = 0.0, ""
    for name in names:
        a, b = columns(os.path.join(out_a, name)), columns(os.path.join(out_b, name))
        largest = max(abs(v) for c in a.values() for v in c)
        for key, values in a.items():
            scale = max([abs(v) for v in values] + [1e-6 * largest])
            for x, y in zip(values, b[key]):
                d = abs(x - y) / scale
                if d > worst:
                    worst, where = d, "%s %s" % (name, key)
    for key, v in (summary_a or {}).get("quantities_of_interest", {}).items():
        d = abs(v - summary_b["quantities_of_interest"][key]) / max(abs(v), 1e-300)
        if d > worst:
            worst, where = d, "quantity " + key
    return worst, where


def histories_agree(out_a, out_b, names, rtol, label):
    """Check that two runs' CSV histories (files @p names, the columns both
    have) agree to @p rtol of each file's largest value: the solver-tolerance
    comparison of an iterative or parallel run against a direct one."""
    for name in names:
        a, b = read_csv(os.path.join(out_a, name)), read_csv(os.path.join(out_b, name))
        keys = [k for k in a if k in b]
        scale = max(max(abs(x) for x in a[k]) for k in keys) or 1.0
        worst = max(abs(x - y) for k in keys for x, y in zip(a[k], b[k]))
        check(worst <= rtol * scale, "%s, %s: largest difference %.2e (relative %.1e <= %.0e)"
              % (label, name, worst, worst / scale, rtol))

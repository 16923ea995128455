"""Helpers for anvil's scene tests: run the program, read what it wrote.

Every test derives its expected values independently of anvil (closed forms,
convergence orders, energy balances); this module only runs and reads.
"""
import csv
import json
import os
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


def read_csv(path):
    """Columns of a CSV file as a dict of float lists."""
    with open(path) as f:
        rows = list(csv.DictReader(f))
    return {k: [float(r[k]) for r in rows] for k in rows[0].keys()} if rows else {}


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

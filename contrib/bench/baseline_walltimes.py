#!/usr/bin/env python3
"""Wall time of every full shipped scene (prm/*.prm, as shipped, one process),
written to contrib/bench/baseline_walltimes.json with the commit and the
machine, so that a benchmark after a refactor can print before/after.

A scene that takes less than QUICK seconds is run three times (median), a
longer one once. The load average is recorded beside the times: on a machine
shared with other jobs the times are only comparable at a similar load.

Usage: contrib/bench/baseline_walltimes.py BUILD_DIR [scene ...] [--output FILE]
"""
import glob
import json
import os
import platform
import statistics
import subprocess
import sys
import tempfile
import time

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
QUICK = 20.0  # s


def run_once(anvil, scene, out):
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
               DEAL_II_NUM_THREADS="1")
    start = time.time()
    subprocess.run([anvil, scene, "--set", "Output/Directory=" + out], check=True,
                   stdout=subprocess.DEVNULL, env=env)
    seconds = time.time() - start
    with open(os.path.join(out, "summary.json")) as f:
        summary = json.load(f)
    return seconds, summary


def time_scene(anvil, scene):
    """Median of 3 (quick scenes) or 1 run: wall seconds, the program's own
    wall_time, steps and Newton iterations (to see that the same work was done)."""
    runs = []
    with tempfile.TemporaryDirectory() as tmp:
        while True:
            seconds, summary = run_once(anvil, scene, os.path.join(tmp, str(len(runs))))
            runs.append((seconds, summary["wall_time"]))
            if runs[0][0] >= QUICK or len(runs) == 3:
                break
    return {"runs": len(runs), "wall_seconds": statistics.median(r[0] for r in runs),
            "program_wall_time": statistics.median(r[1] for r in runs),
            "all_wall_seconds": [round(r[0], 3) for r in runs],
            "steps": summary["steps"], "newton_iterations": summary["newton_iterations"],
            "load_average_after": round(os.getloadavg()[0], 2)}


def machine():
    model = next((line.split(":", 1)[1].strip() for line in open("/proc/cpuinfo")
                  if line.startswith("model name")), platform.processor())
    return {"nproc": os.cpu_count(), "cpu_model": model, "system": platform.platform()}


def main(argv):
    output = os.path.join(ROOT, "contrib", "bench", "baseline_walltimes.json")
    if "--output" in argv:
        i = argv.index("--output")
        output = argv[i + 1]
        del argv[i:i + 2]
    anvil = os.path.join(os.path.abspath(argv[0]), "anvil")
    scenes = argv[1:] or sorted(glob.glob(os.path.join(ROOT, "prm", "*.prm")))
    git = lambda *a: subprocess.run(["git", "-C", ROOT] + list(a), capture_output=True,
                                    text=True).stdout.strip()
    # The last commit that changed the program (tests and scripts do not move times).
    code_commit = git("log", "-1", "--format=%H", "--", "source", "include", "CMakeLists.txt", "cmake")
    result = {"commit": git("rev-parse", "HEAD"), "code_commit": code_commit,
              "machine": machine(), "processes": 1,
              "note": "full shipped scenes as shipped (fields written), one process, "
                      "DEAL_II_NUM_THREADS=1; median of 3 runs below %g s, else 1 run" % QUICK,
              "scenes": {}}
    for scene in scenes:
        name = os.path.splitext(os.path.basename(scene))[0]
        result["scenes"][name] = time_scene(anvil, scene)
        print("%-22s %8.2f s (%d run(s))" % (name, result["scenes"][name]["wall_seconds"],
                                              result["scenes"][name]["runs"]), flush=True)
    with open(output, "w") as f:
        json.dump(result, f, indent=1)
        f.write("\n")


if __name__ == "__main__":
    main(sys.argv[1:])

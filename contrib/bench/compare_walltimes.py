#!/usr/bin/env python3
"""Before/after wall time of every shipped scene: runs them now (as
baseline_walltimes.py does) and prints them beside contrib/bench/
baseline_walltimes.json (the times before the parts refactor), with the
steps and Newton iterations of both so one sees the same work was done.
Prints figures, asserts nothing: times on a shared machine are noisy, so the
load average of both measurements is printed too.

Usage: contrib/bench/compare_walltimes.py BUILD_DIR [scene ...]
"""
import json
import os
import sys
import tempfile

sys.path.insert(0, os.path.dirname(__file__))
import baseline_walltimes as bw  # noqa: E402


def main(argv):
    with open(os.path.join(bw.ROOT, "contrib", "bench", "baseline_walltimes.json")) as f:
        before = json.load(f)
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "now.json")
        bw.main(argv + ["--output", out])
        with open(out) as f:
            now = json.load(f)
    print("\nshipped scenes, one process: before (%s) and now (%s)"
          % (before["code_commit"][:8], now["code_commit"][:8]))
    print("%-22s %9s %9s %7s  %9s %9s  %6s %6s" % ("scene", "before s", "now s", "ratio",
                                                  "prog. bef", "prog. now", "steps", "Newton"))
    for name, b in sorted(before["scenes"].items()):
        n = now["scenes"].get(name)
        if not n:
            continue
        same = "same" if (b["steps"], b["newton_iterations"]) == (n["steps"], n["newton_iterations"]) else "DIFF"
        print("%-22s %9.2f %9.2f %7.2f  %9.3f %9.3f  %6d %6s" % (
            name, b["wall_seconds"], n["wall_seconds"], n["wall_seconds"] / b["wall_seconds"],
            b["program_wall_time"], n["program_wall_time"], n["steps"], same))
    print("load average: before %.1f, now %.1f (times are comparable only at similar load)"
          % (max(s["load_average_after"] for s in before["scenes"].values()),
             max(s["load_average_after"] for s in now["scenes"].values())))


if __name__ == "__main__":
    main(sys.argv[1:])

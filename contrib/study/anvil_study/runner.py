"""Running anvil for a study: one process per run (or mpirun -np N), several
at once, each run remembered in OUT/runs/<key>/record.json so that a study
interrupted and started again skips the runs it already has.

The key is a hash of what determines the run's results (its scene, the
--set overrides in order, the process count), so a changed study reruns
exactly the runs that changed. The record is written (atomically) only when
all repeats of a run are done: a run killed half-way is simply run again.
"""
import concurrent.futures
import csv
import hashlib
import json
import os
import subprocess
import sys
import threading
import time

ENV = {"OMPI_ALLOW_RUN_AS_ROOT": "1", "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM": "1"}


def strip_unit(name):
    """'reaction_x [N]' -> 'reaction_x': columns and quantities may carry units."""
    return name.split(" [", 1)[0].strip()


def run_key(scene, overrides, np):
    # The last value of each entry wins (as in anvil), so the key is of the
    # entries in sorted order: the same run reached two ways is one run.
    text = json.dumps([os.path.abspath(scene), sorted(dict(overrides).items()), np])
    return hashlib.sha1(text.encode()).hexdigest()[:12]


def read_columns(path):
    """A CSV history as {name without unit: [float]}; non-numeric cells -> nan."""
    with open(path) as f:
        rows = list(csv.reader(f))
    if not rows:
        return {}
    head, out = [strip_unit(h) for h in rows[0]], {}
    for j, h in enumerate(head):
        col = []
        for r in rows[1:]:
            try:
                col.append(float(r[j]))
            except (ValueError, IndexError):
                col.append(float("nan"))
        out[h] = col
    return out


def failure_reason(returncode, stdout, stderr, timed_out, timeout):
    if timed_out:
        return "timeout", "killed after the study's Timeout of %g s" % timeout
    if returncode == 0:
        return "completed", ""
    lines = [l.strip() for l in (stderr + "\n" + stdout).split("\n") if l.strip()]
    for marker in ("simulation stopped:", "error:", "internal error:"):
        for l in lines:
            if marker in l:
                return ("failed" if returncode == 3 else "error"), l.split(marker, 1)[1].strip()
    return "error", "exit status %d%s" % (returncode, (": " + lines[-1]) if lines else "")


class Runner:
    """Runs specs (dicts with 'key' and 'overrides') and returns their records."""

    def __init__(self, anvil, scene, out_dir, np=1, jobs=1, threads=0, timeout=0, repeats=1, histories=(),
                 log=sys.stdout):
        self.anvil, self.scene, self.out_dir = anvil, scene, out_dir
        self.np, self.repeats, self.timeout = np, repeats, timeout
        self.jobs = jobs if jobs > 0 else max(1, (os.cpu_count() or 1) // np)
        # Threads per run: the cores shared among the runs that go at once.
        self.threads = threads if threads > 0 else max(1, (os.cpu_count() or 1) // (self.jobs * np))
        self.histories = list(histories)     # [(file, column)] to keep from each run
        self.log, self.lock = log, threading.Lock()
        self.executed, self.reused, self.run_wall, self.phase_wall = 0, 0, 0.0, 0.0

    def spec(self, overrides, label=""):
        return {"key": run_key(self.scene, overrides, self.np), "overrides": overrides, "label": label}

    def command(self, spec, out):
        cmd = [self.anvil, self.scene, "--set", "Output/Directory=" + out, "--threads", str(self.threads)]
        for path, value in spec["overrides"]:
            cmd += ["--set", "%s=%s" % (path, value)]
        if self.np > 1:
            cmd = ["mpirun", "-np", str(self.np), "--oversubscribe"] + cmd
        return cmd

    def record_path(self, key):
        return os.path.join(self.out_dir, "runs", key, "record.json")

    def cached(self, spec):
        path = self.record_path(spec["key"])
        if not os.path.exists(path):
            return None
        try:
            with open(path) as f:
                rec = json.load(f)
        except (OSError, ValueError):
            return None
        if rec.get("overrides") != [list(o) for o in spec["overrides"]] or len(rec.get("wall_times", [])) < self.repeats:
            return None
        return rec

    def _execute(self, spec):
        run_dir = os.path.dirname(self.record_path(spec["key"]))
        out = os.path.join(run_dir, "out")
        os.makedirs(run_dir, exist_ok=True)
        env = dict(os.environ, **ENV)
        walls, status, reason, summary = [], "completed", "", {}
        for _ in range(self.repeats):
            start = time.perf_counter()
            timed_out = False
            with open(os.path.join(run_dir, "stdout.txt"), "w") as so, open(os.path.join(run_dir, "stderr.txt"), "w") as se:
                # Same process group as the tool: stopping the study (Ctrl-C, a
                # kill of its group) stops its runs too.
                p = subprocess.Popen(self.command(spec, out), stdout=so, stderr=se, env=env)
                try:
                    p.wait(timeout=self.timeout or None)
                except subprocess.TimeoutExpired:
                    p.kill()
                    p.wait()
                    timed_out = True
            walls.append(time.perf_counter() - start)
            with open(os.path.join(run_dir, "stdout.txt")) as so, open(os.path.join(run_dir, "stderr.txt")) as se:
                status, reason = failure_reason(p.returncode, so.read(), se.read(), timed_out, self.timeout)
            # Relative to the study folder: the same table wherever the study lives.
            reason = reason.replace(out, os.path.join("runs", spec["key"], "out"))
            if status != "completed":
                break   # a failed run is not timed again
        try:
            with open(os.path.join(out, "summary.json")) as f:
                summary = json.load(f)
        except (OSError, ValueError):
            summary = {}
        histories = {}
        for file, column in self.histories:
            path = os.path.join(out, file)
            if os.path.exists(path):
                cols = read_columns(path)
                if column in cols and "time" in cols:
                    histories["%s:%s" % (file, column)] = [cols["time"], cols[column]]
        rec = {"key": spec["key"], "overrides": [list(o) for o in spec["overrides"]], "np": self.np,
               "threads": self.threads, "status": status, "reason": reason, "wall_times": walls,
               "summary": summary, "histories": histories, "output": out}
        tmp = self.record_path(spec["key"]) + ".tmp"
        with open(tmp, "w") as f:
            json.dump(rec, f)
        os.replace(tmp, self.record_path(spec["key"]))
        return rec

    def run_all(self, specs):
        """Records of all specs (cached ones reused), in the order of specs."""
        records, todo = {}, []
        for s in specs:
            if s["key"] in records:
                continue
            rec = self.cached(s)
            if rec is not None:
                records[s["key"]] = rec
                self.reused += 1
            elif s["key"] not in [t["key"] for t in todo]:
                todo.append(s)
        if todo:
            self.say("running %d run(s) (%d already done), %d at once, %d process(es) x %d thread(s) each"
                     % (len(todo), len(records), min(self.jobs, len(todo)), self.np, self.threads))
        start = time.perf_counter()
        with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, self.jobs)) as pool:
            futures = {pool.submit(self._execute, s): s for s in todo}
            for f in concurrent.futures.as_completed(futures):
                s, rec = futures[f], f.result()
                records[s["key"]] = rec
                self.executed += 1
                self.run_wall += sum(rec["wall_times"])
                self.say("  %-8s %6.2f s  %s%s" % (rec["status"], sum(rec["wall_times"]) / len(rec["wall_times"]),
                                                   s.get("label") or s["key"],
                                                   ("  (" + rec["reason"] + ")") if rec["reason"] else ""))
        self.phase_wall += time.perf_counter() - start
        return [records[s["key"]] for s in specs]

    def say(self, text):
        with self.lock:
            print(text, file=self.log, flush=True)


def check_scene(anvil, scene, overrides):
    """anvil --check with the overrides: '' if valid, else anvil's error line."""
    cmd = [anvil, scene, "--check"]
    for path, value in overrides:
        cmd += ["--set", "%s=%s" % (path, value)]
    p = subprocess.run(cmd, capture_output=True, text=True, env=dict(os.environ, **ENV))
    if p.returncode == 0:
        return ""
    lines = [l for l in (p.stderr + p.stdout).split("\n") if l.strip()]
    line = next((l for l in lines if "error" in l), lines[-1] if lines else "exit status %d" % p.returncode)
    return line.replace("anvil: error: ", "").strip()


def scene_parameters(anvil, scene, overrides):
    """The scene as anvil reads it (--print-parameters with the overrides):
    {'Section/Entry': value}."""
    cmd = [anvil, "--print-parameters", scene]
    for path, value in overrides:
        cmd += ["--set", "%s=%s" % (path, value)]
    p = subprocess.run(cmd, capture_output=True, text=True, env=dict(os.environ, **ENV))
    values, stack = {}, []
    for line in p.stdout.split("\n"):
        t = line.split("#", 1)[0].strip()
        if t.startswith("subsection "):
            stack.append(" ".join(t[11:].split()))
        elif t == "end" and stack:
            stack.pop()
        elif t.startswith("set ") and "=" in t:
            k, v = t[4:].split("=", 1)
            values["/".join(stack + [" ".join(k.split())])] = v.strip()
    return values

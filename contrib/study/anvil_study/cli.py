"""anvil-study STUDY.prm [--set 'Section/Entry=value']... [options]: run a
study (doc/study.md). Exit status 0 done (runs that failed are reported in
the table, they do not stop the study), 2 bad input (one line, before any run).
"""
import argparse
import concurrent.futures
import json
import os
import sys
import time

from . import analysis as A
from . import ladder as LD
from . import report as R
from .runner import Runner, check_scene, scene_parameters, strip_unit
from .studyfile import StudyInputError, read_study


def parse_args(argv):
    p = argparse.ArgumentParser(prog="anvil --study", description="Run a study (doc/study.md): ladders of scene "
                                "entries with work-precision tables and plots, stability maps, physics cost.")

    def one_line(message):      # bad input: one line, exit 2 (argparse would print its usage too)
        print("anvil-study: error: %s (see anvil --study -h)" % message, file=sys.stderr)
        sys.exit(2)
    p.error = one_line
    p.add_argument("study", help="the study file (ParameterHandler format, doc/study.md)")
    p.add_argument("--set", action="append", default=[], metavar="'Section/Entry=value'",
                   help="scene override applied to every run (repeatable)")
    p.add_argument("--output", help="output directory (default: Study/Output directory)")
    p.add_argument("--jobs", type=int, help="runs at once (default: Study/Concurrent runs; 0: the cores)")
    p.add_argument("--np", type=int, help="MPI processes per run (default: Study/MPI processes)")
    p.add_argument("--repeats", type=int, help="timing repeats per run (default: Study/Repeats)")
    p.add_argument("--check", action="store_true", help="check the study and its scene, run nothing")
    p.add_argument("--anvil", default=os.environ.get("ANVIL_EXECUTABLE", "anvil"), help="the anvil executable")
    return p.parse_args(argv)


def fail(text):
    print("anvil-study: error: " + text, file=sys.stderr)
    return 2


def cli_overrides(sets, path):
    out = []
    for s in sets:
        if "=" not in s or "/" not in s.split("=", 1)[0]:
            raise StudyInputError("%s: --set '%s': expected 'Section/Entry=value'" % (path, s))
        k, v = s.split("=", 1)
        if k.strip().split("/")[0] in ("Study", "Set", "Quantities", "Reference", "Stability", "Physics cost") \
                or k.strip().startswith("Ladder"):
            raise StudyInputError("%s: --set '%s': --set changes the scene's entries; the study's own "
                                  "(subsection %s) are options (--jobs, --repeats, --output) or lines "
                                  "of the study file" % (path, s, k.strip().split("/")[0]))
        out.append((k.strip(), v.strip()))
    return out


def check_input(study, anvil, cli_sets, extra=()):
    """Everything that can be checked before a run: the scene with the base
    overrides, each ladder level (anvil --check), the quantities of interest."""
    base = list(study.sets) + cli_sets
    # Optional levels (a scheme this build may not have, e.g. 'monolithic'):
    # dropped, with a note, when anvil --check rejects them.
    for ladder in study.ladders:
        for label in list(ladder.optional):
            i = ladder.entries[0][1].index(label)
            ov = [(p, v) for p, v in base if "{" not in v] + [(p, v) for p, v in ladder.overrides(i) if "{" not in v]
            if check_scene(anvil, study.scene, ov):
                print("anvil-study: note: ladder '%s': level '%s' is not available in this build, left out"
                      % (ladder.name, label))
                ladder.drop(i)
    # The base entries and level k of every ladder in one --check (shorter
    # ladders repeat their last level); the checks, the reference run's and
    # the reading of the scene's quantities go at once (they are start-ups).
    n = max([len(l) for l in study.ladders] + [1])
    sets = []
    for k in range(n):
        levels = [min(k, len(l) - 1) for l in study.ladders]
        variables = A.variables_of(study.ladders, levels)
        try:
            sets.append([(p, A.substitute(v, variables, p)) for p, v in base] +
                        A.overrides_of(study.ladders, levels, variables) +
                        [(p, A.substitute(v, variables, p)) for p, v in extra])
        except ValueError as e:
            raise StudyInputError("%s: %s" % (study.path, e))
    if study.reference_type == "run":
        sets.append(base + list(study.reference_run))
    with concurrent.futures.ThreadPoolExecutor(max_workers=max(2, os.cpu_count() or 1)) as pool:
        qois = pool.submit(scene_parameters, anvil, study.scene, sets[0])
        errors = list(pool.map(lambda ov: check_scene(anvil, study.scene, ov), sets))
        qois = qois.result().get("Output/Quantities of interest", "")
    for k, err in enumerate(errors):
        if not err:
            continue
        if k == n:
            raise StudyInputError("%s: Reference/Run: anvil --check: %s" % (study.path, err))
        culprit = next((l for l in study.ladders for p, _ in l.entries if p in err), None)
        where = ("ladder '%s' (line %d), level %d" % (culprit.name, culprit.line, k + 1)) if culprit \
            else "the scene with the study's entries" + (" (ladder level %d)" % (k + 1) if study.ladders else "")
        raise StudyInputError("%s: %s: anvil --check: %s" % (study.path, where, err))
    names = [strip_unit(x.split(":", 1)[0]) for x in qois.split(";") if ":" in x]
    for q in study.quantities:
        if q.kind == "summary" and "." not in q.key and strip_unit(q.key) not in names:
            raise StudyInputError("%s:%d: quantity '%s': the scene has no quantity of interest '%s' (it has: %s; "
                                  "or give a summary.json path like heat.balance_error)"
                                  % (study.path, q.line, q.name, q.key, ", ".join(names) or "none"))


def _at(value, name, x):
    """A Stability entry with the variable fixed (the ladder values stay free)."""
    return value.replace("{", "{(lambda %s: " % name).replace("}", ")(%r)}" % x)


def run_ladder(study, runner, cli_sets, out):
    specs, ref_spec = LD.plan(study, runner, cli_sets)
    all_specs = specs + ([ref_spec] if ref_spec else [])
    records = runner.run_all(all_specs)
    ref_record = records[-1] if ref_spec else None
    if ref_record is not None and ref_record["status"] != "completed":
        print("anvil-study: the reference run did not complete (%s): errors are not available"
              % ref_record["reason"])
    rows = LD.evaluate_runs(study, specs, records[:len(specs)], ref_record)
    order_list = LD.orders(study, rows)
    R.write_csv(study, rows, os.path.join(out, "study.csv"))
    lines = R.summary_lines(study, rows, order_list)
    with open(os.path.join(out, "study.md"), "w") as f:
        f.write("\n".join(lines) + "\n")
    with open(os.path.join(out, "orders.json"), "w") as f:
        json.dump(order_list, f, indent=1)
    R.plot_work_precision(study, rows, os.path.join(out, "work_precision.png"))
    R.plot_convergence(study, order_list, os.path.join(out, "convergence.png"))
    return rows


def main(argv):
    args = parse_args(argv)
    started = time.perf_counter()
    try:
        study = read_study(args.study)
        cli_sets = cli_overrides(args.set, args.study)
        if args.repeats is not None:
            if args.repeats < 1:
                raise StudyInputError("%s: --repeats %d: expected at least 1" % (args.study, args.repeats))
            study.repeats = args.repeats
        extra = []
        if study.mode == "stability":
            from .stability import read_stability
            stab = read_stability(study)
            # The scene entries that follow the bisected variable, checked at the top of its range.
            extra = [(p, _at(v, stab.variable, stab.hi)) for p, v in stab.entries]
        check_input(study, args.anvil, cli_sets, extra)
        for name, entries in study.variants if study.mode == "physics cost" else []:
            err = check_scene(args.anvil, study.scene, list(study.sets) + list(entries) + cli_sets)
            if err:
                raise StudyInputError("%s: Physics cost variant '%s': anvil --check: %s" % (study.path, name, err))
    except StudyInputError as e:
        return fail(str(e))
    checked = time.perf_counter()
    if args.check:
        print("anvil-study: %s is valid (%s study of %s)" % (args.study, study.mode, study.scene))
        return 0
    out = args.output or study.output
    os.makedirs(out, exist_ok=True)
    histories = [(q.file, q.key) for q in study.quantities if q.kind == "history"] + \
        list(getattr(study, "histories", []))
    runner = Runner(args.anvil, study.scene, out, np=args.np or study.np,
                    jobs=args.jobs if args.jobs is not None else study.jobs, threads=study.threads,
                    timeout=study.timeout, repeats=study.repeats, histories=histories)
    if study.mode == "ladder":
        run_ladder(study, runner, cli_sets, out)
        written = "study.csv, study.md, work_precision.png, convergence.png"
    elif study.mode == "stability":
        from .stability import run_stability
        run_stability(study, stab, runner, cli_sets, out)
        written = "stability.csv, stability.md, stability.png"
    else:
        from .physics_cost import run_physics_cost
        run_physics_cost(study, runner, cli_sets, out)
        written = "physics_cost.csv, physics_cost.md"
    total = time.perf_counter() - started
    # Overhead: what the study costs beyond its runs (reading, checking, tables, figures).
    print("anvil-study: %s: %d run(s) executed, %d reused; wall time %.2f s, sum of the runs %.2f s; wrote %s in %s"
          % (study.name, runner.executed, runner.reused, total, runner.run_wall, written, out))
    with open(os.path.join(out, "timing.json"), "w") as f:
        json.dump({"study_wall": total, "check_wall": checked - started, "runs_phase_wall": runner.phase_wall,
                   "runs_wall_sum": runner.run_wall, "executed": runner.executed,
                   "reused": runner.reused, "jobs": runner.jobs, "threads": runner.threads}, f)
    return 0

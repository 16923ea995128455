"""Issue 15's Newton ratio counted in instructions (callgrind), which a loaded machine does not move.

Per shipped scene with mechanics (perf.py's list; the tube to 0.25 ms), one process, one thread,
under callgrind:
  - steps: the instructions of the step loop (Simulator::run_steps less what is paid once per
    run or per output: the mesh, MechanicalProblem::setup, the rest of the set-up before the
    first step, the initial and accepted outputs, checkpoints, the closing of the histories and
    the summary) — what perf.py's wall ratio counts for a heat-less scene;
  - newton: MechanicalProblem::solve_step, what its CPU ratio counts;
  - one: the instructions of one assembly with the tangent (every call of
    MechanicalProblem::assemble(true) through newton.cc's tangent_assembly) plus one
    MechanicalProblem::solve_linear_system, each the mean over its calls;
  - the instruction ratio steps / Newton iterations / one (the heat scenes' wall ratio counts
    solve_step alone: newton / Newton iterations / one) and the Newton ratio newton / Newton
    iterations / one;
  - per Newton iteration, in units of one: the tangent assemblies, the residual-only
    evaluations, the linear solves, the rest of solve_step, the commit (the heat's part
    apart), the histories written per attempt, the step line, the rest of the loop.

    python3 contrib/bench/instruction_ratio.py BUILD_DIR OUT_DIR [--only NAME[,NAME...]]
    python3 contrib/bench/instruction_ratio.py --parse CALLGRIND_OUT SUMMARY_JSON

Each scene's callgrind file stays in OUT_DIR (ir_NAME.cg); --parse reads one again.
"""
import json
import os
import re
import subprocess
import sys


def read_callgrind(path):
    """Self cost per function and (calls, inclusive cost) per caller -> callee, first event."""
    names = {}
    self_cost, arcs = {}, {}
    n_positions = 1
    fn = None
    callee, pending = None, 0
    totals = 0

    def name_of(spec):
        m = re.match(r"\((\d+)\)(?: (.*))?$", spec)
        if not m:
            return spec
        if m.group(2) is not None:
            names[m.group(1)] = m.group(2)
        return names[m.group(1)]

    with open(path, errors="replace") as f:
        for line in f:
            if not line or line[0] == "#" or line == "\n":
                continue
            c = line[0]
            if c.isdigit() or c in "+-*":
                parts = line.split()
                cost = int(parts[n_positions]) if len(parts) > n_positions else 0
                if pending:
                    a = arcs.setdefault((fn, callee), [0, 0])
                    a[0] += pending
                    a[1] += cost
                    pending = 0
                else:
                    self_cost[fn] = self_cost.get(fn, 0) + cost
                continue
            key, _, value = line.rstrip("\n").partition("=")
            if key == "fn":
                fn = name_of(value)
            elif key == "cfn":
                callee = name_of(value)
            elif key == "calls":
                pending = int(value.split()[0])
            elif key in ("fl", "fi", "fe", "cfl", "cfi", "ob", "cob"):
                name_of(value) if key in ("ob", "cob") else None
            elif line.startswith("positions:"):
                n_positions = len(line.split()[1:])
            elif line.startswith("totals:") or line.startswith("summary:"):
                totals = max(totals, int(line.split()[1]))
    return self_cost, arcs, totals


class Profile:
    def __init__(self, path):
        self.self_cost, self.arcs, self.total = read_callgrind(path)
        self.out, self.into = {}, {}
        for (a, b), v in self.arcs.items():
            self.out.setdefault(a, []).append((b, v))
            self.into.setdefault(b, []).append((a, v))

    def functions(self, pattern):
        r = re.compile(pattern)
        return [f for f in set(self.self_cost) | set(self.into) if r.search(f)]

    def inclusive(self, pattern):
        """Inclusive cost of the matching functions, counted where they are entered from a
        function that does not match (recursion and nesting among them counted once)."""
        r = re.compile(pattern)
        cost = calls = 0
        for f in self.functions(pattern):
            for caller, (n, c) in self.into.get(f, []):
                if not r.search(caller):
                    calls += n
                    cost += c
        return cost, calls

    def called_from(self, caller_pattern, callee_pattern):
        """Inclusive cost and calls of the arcs from the callers to the callees."""
        rc, re_ = re.compile(caller_pattern), re.compile(callee_pattern)
        cost = calls = 0
        for (a, b), (n, c) in self.arcs.items():
            if rc.search(a) and re_.search(b) and not rc.search(b):
                cost += c
                calls += n
        return cost, calls


D = r"<[23]>"
LOOP = r"anvil::Simulator" + D + r"::run_steps\(\)"
# Paid once per run or per output, called from the step loop's function.
ONCE = [r"anvil::Simulator" + D + r"::setup\(\)", r"::check_against_mesh\(\)",
        r"anvil::CoupledProblem" + D + r"::setup\(", r"::initialize\(anvil::CoupledProblem",
        r"::print_start\(\)", r"::start\(anvil::SimulationState", r"::initial\(anvil::SimulationState",
        r"::read_checkpoint\(", r"::restarted\(\)", r"::finish\(anvil::SimulationState",
        r"::write_summary\(", r"TimerOutput::print_summary", r"::print_results\(\)",
        r"::quantities_of_interest\(\)", r"resident_memory_mb", r"TimerOutput::TimerOutput\(",
        r"std::filesystem::.*create_directories", r"::output_step\(", r"::write_checkpoint\(",
        r"::stop\(std::", r"TimerOutput::~TimerOutput", r"PMPI_Barrier|MPI_Barrier"]


def analyse(cg, summary):
    p = Profile(cg)
    s = json.load(open(summary))
    newton_iterations = max(1, int(s["newton_iterations"]))
    loop_fn = p.functions(LOOP)
    if not loop_fn:
        loop_fn = p.functions(r"anvil::Simulator" + D + r"::run\(\)")
    loop_re = "|".join(re.escape(f) for f in loop_fn)
    loop, _ = p.inclusive(loop_re)
    once = sum(p.called_from(loop_re, pat)[0] for pat in ONCE)
    steps = loop - once
    # perf.py's definition of sessions <= 23: the solver's time less the mesh,
    # 'Mechanics: setup', outputs and checkpoints (the summary's clock stops
    # in write_summary: what follows it is not in the solver's time).
    old = loop - sum(p.called_from(loop_re, pat)[0] for pat in
                     (ONCE[0], r"::output_step\(", r"::initial\(anvil::SimulationState", r"::write_checkpoint\(",
                      r"::write_summary\(", r"TimerOutput::print_summary", r"::print_results\(\)",
                      r"::quantities_of_interest\(\)", r"TimerOutput::~TimerOutput")) \
        - p.inclusive(r"anvil::MechanicalProblem" + D + r"::setup\(\)")[0]
    newton, _ = p.inclusive(r"anvil::MechanicalProblem" + D + r"::solve_step\(")
    tangent, n_tangent = p.inclusive(r"tangent_assembly<")
    residual, n_residual = p.inclusive(r"residual_assembly<")
    solve, n_solve = p.inclusive(r"anvil::MechanicalProblem" + D + r"::solve_linear_system\(")
    assemble_all, n_assemble_all = p.inclusive(r"anvil::MechanicalProblem" + D + r"::assemble\(bool, double\)")
    if n_tangent == 0:
        print("  %s: total %.1f M, step loop %.1f M, solve_step %.1f M, %d Newton; no tangent_assembly "
              "symbol (a build without newton.cc's counting wrappers): no ratio" % (
                  cg, p.total / 1e6, steps / 1e6, newton / 1e6, newton_iterations))
        return None
    one = tangent / n_tangent + (solve / n_solve if n_solve else 0.)
    # scheme->commit(t_old, t_new), or CoupledProblem::commit(dt) where that is inlined.
    commit, _ = p.called_from(loop_re, r"::commit\(double")
    mech_commit, _ = p.inclusive(r"anvil::MechanicalProblem" + D + r"::commit_step\(\)")
    heat_commit = commit - mech_commit
    attempt, _ = p.called_from(loop_re, r"::attempt\(anvil::SimulationState")
    print_step, _ = p.called_from(loop_re, r"::print_step\(")
    heat, _ = p.inclusive(r"anvil::CoupledProblem" + D + r"::solve_heat\(")
    enter, n_enter = p.inclusive(r"dealii::TimerOutput::enter_subsection\(")
    leave, _ = p.inclusive(r"dealii::TimerOutput::leave_subsection\(")
    per = lambda x: x / newton_iterations / one
    heat_scene = s.get("temperature_dofs", 0) > 0
    return dict(
        total=p.total, loop=loop, once=once, steps=steps, newton=newton, tangent=tangent,
        n_tangent=n_tangent, residual=residual, n_residual=n_residual, solve=solve, n_solve=n_solve,
        other_assemble=assemble_all - tangent - residual, one=one, newton_iterations=newton_iterations,
        timers=enter + leave, timer_scopes=n_enter,
        old_ratio=(newton if heat_scene else old) / newton_iterations / one,
        steps_count=s["steps"], ratio=per(newton if heat_scene else steps - heat), newton_ratio=per(newton),
        parts=dict(tangent=per(tangent), residual=per(residual), solve=per(solve),
                   newton_rest=per(newton - tangent - residual - solve),
                   commit=per(mech_commit), attempt=per(attempt), print_step=per(print_step),
                   heat=per(heat + heat_commit),
                   loop_rest=per(steps - newton - commit - attempt - print_step - heat))), heat_scene


def report(name, r):
    if r is None:
        return
    r, heat_scene = r
    q = r["parts"]
    print("%-20s %8.0f %8.0f %8.0f %6d %6d %8.2f %7.3f %7.3f %7.3f | %5.2f %5.2f %5.2f %5.2f %5.2f %5.2f %5.2f %5.2f %5.2f" % (
        name + (" *" if heat_scene else ""), r["total"] / 1e6, r["steps"] / 1e6, r["newton"] / 1e6,
        r["steps_count"], r["newton_iterations"], r["one"] / 1e6, r["ratio"], r["old_ratio"], r["newton_ratio"],
        q["tangent"], q["residual"], q["solve"], q["newton_rest"], q["commit"], q["heat"], q["attempt"],
        q["print_step"], q["loop_rest"]))
    print("%-20s timers: %d scopes, %.0f instructions each, %.3f of one per Newton iteration; assemblies: %d with "
          "the tangent (%.2f M each), %d residual-only (%.2f M each), %d linear solves (%.2f M each)%s" % (
              "", r["timer_scopes"], r["timers"] / max(1, r["timer_scopes"]), r["timers"] / r["newton_iterations"] / r["one"],
              r["n_tangent"], r["tangent"] / r["n_tangent"] / 1e6, r["n_residual"],
              r["residual"] / max(1, r["n_residual"]) / 1e6, r["n_solve"], r["solve"] / max(1, r["n_solve"]) / 1e6,
              "; other assemble() calls %.1f M" % (r["other_assemble"] / 1e6) if r["other_assemble"] > 0 else ""))


HEADER = ("%-20s %8s %8s %8s %6s %6s %8s %7s %7s %7s | %5s %5s %5s %5s %5s %5s %5s %5s %5s" % (
    "scene", "total M", "steps M", "newton M", "steps", "Newton", "one M", "ratio", "(old)", "newton",
    "K+R", "resid", "solve", "nrest", "commt", "heat", "attmp", "line", "rest"))
LEGEND = (
    "  total: whole process; steps: the step loop less once-only and output work (the heat "
    "included); newton: solve_step; one: one assembly with the "
    "tangent + one linear solve (means); ratio: steps\n  (heat scenes, *: solve_step, as "
    "perf.py's mechanics_wall_time) / Newton / one; (old): the same by perf.py's definition of\n  sessions <= 23 "
    "(set-up but mesh and 'Mechanics: setup', and the closing, counted); newton: solve_step / Newton / one.\n"
    "  Per Newton iteration in units of one: K+R tangent assemblies, resid residual-only "
    "evaluations, solve linear\n  solves, nrest the rest of solve_step, commt the mechanics' "
    "commit (audit, Newmark, contact), heat solve_heat and\n  the heat's commit, attmp "
    "newton.csv rows, line the step line, rest the rest of the loop.")


def main():
    if sys.argv[1] == "--parse":
        print(HEADER)
        report(os.path.basename(sys.argv[2]), analyse(sys.argv[2], sys.argv[3]))
        print(LEGEND)
        return
    build, out = sys.argv[1], sys.argv[2]
    only = None
    if "--only" in sys.argv[3:-1]:
        only = set(sys.argv[sys.argv.index("--only") + 1].split(","))
    os.makedirs(out, exist_ok=True)
    root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    cases = [("two_blocks", "prm/two_blocks.prm", []),
             ("necking_bar_thermal", "prm/necking_bar_thermal.prm", []),
             ("tube_025", "prm/tube_impact.prm", ["Time/End time=2.5e-4"])]
    cases += [(os.path.splitext(f)[0], "prm/" + f, [])
              for f in sorted(os.listdir(os.path.join(root, "prm")))
              if f.endswith(".prm") and os.path.splitext(f)[0] not in
              ("two_blocks", "necking_bar_thermal", "tube_impact", "steady_slab", "heat_half_space")]
    # A copied build (an executable and its libanvil.so, e.g. a baseline kept
    # aside) finds its own library first: the executable's RUNPATH yields to it.
    env = dict(os.environ, DEAL_II_NUM_THREADS="1",
               LD_LIBRARY_PATH=os.path.abspath(build) + ":" + os.environ.get("LD_LIBRARY_PATH", ""))
    print("issue 15's Newton ratio in instructions (callgrind, one process, one thread):")
    print(HEADER)
    for name, scene, sets in cases:
        if only is not None and name not in only:
            continue
        d = os.path.join(out, "ir_" + name)
        cg = d + ".cg"
        cmd = ["valgrind", "--tool=callgrind", "--callgrind-out-file=" + cg,
               os.path.join(build, "anvil"), os.path.join(root, scene), "--threads", "1",
               "--set", "Output/Directory=" + d, "--set", "Output/Field interval=0",
               "--set", "Output/Verbosity=normal"]
        for s in sets:
            cmd += ["--set", s]
        with open(d + ".log", "w") as log:
            status = subprocess.call(cmd, stdout=log, stderr=subprocess.STDOUT, env=env)
        if status != 0 or not os.path.exists(d + "/summary.json"):
            print("%-20s anvil exited with status %d (see %s.log)" % (name, status, d))
            continue
        report(name, analyse(cg, d + "/summary.json"))
        sys.stdout.flush()
    print(LEGEND)


if __name__ == "__main__":
    main()

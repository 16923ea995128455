"""Stability maps: over the grid of the study's ladders (one curve per
scheme), the largest value of one variable (a time step, a coupling number,
a penalty, ...) at which a run stays stable, found by bisection.

A trial is unstable when the run does not complete, when the step-to-step
changes of the monitored history grow (the mean |change| over the last third
of the steps after loading exceeds that over the first third: a growing
oscillation, or a drift that accelerates), or when the balance error grows
tenfold from the first half of the run to the second. Changes below 1e-6 of
the loading changes are round-off, not oscillation.
"""
import csv
import math
import os

from . import analysis as A
from .runner import read_columns, strip_unit
from .studyfile import StudyInputError, scene_entries

KEYS = ("Variable", "Range", "Scale", "Bisections", "Monitor", "Skip", "Balance", "Predicted")


class Stability:
    pass


def _history_spec(text, path, line, what):
    if ":" not in text or not text.split(":", 1)[0].strip().endswith(".csv"):
        raise StudyInputError("%s:%d: Stability/%s: expected 'FILE.csv: COLUMN', not '%s'" % (path, line, what, text))
    f, c = text.split(":", 1)
    return f.strip(), strip_unit(c.strip())


def read_stability(study):
    node, path = study.stability, study.path
    for name, (_, line) in node.entries.items():
        if name not in KEYS:
            raise StudyInputError("%s:%d: unknown entry '%s' in subsection Stability (expected one of: %s)"
                                  % (path, line, name, ", ".join(KEYS)))
    get = lambda k, d="": node.entries.get(k, (d, node.line))
    s = Stability()
    s.variable, line = get("Variable")
    if not s.variable.isidentifier():
        raise StudyInputError("%s:%d: Stability/Variable: expected a name (used as {name} in Entries), not '%s'"
                              % (path, line, s.variable))
    text, line = get("Range")
    try:
        s.lo, s.hi = [float(x) for x in text.split(",")]
    except ValueError:
        raise StudyInputError("%s:%d: Stability/Range: expected 'lowest, highest', not '%s'" % (path, line, text))
    if not 0 < s.lo < s.hi if get("Scale", "log")[0] == "log" else not s.lo < s.hi:
        raise StudyInputError("%s:%d: Stability/Range: expected lowest < highest (> 0 on a log scale), not '%s'"
                              % (path, line, text))
    s.scale, line = get("Scale", "log")
    if s.scale not in ("log", "linear"):
        raise StudyInputError("%s:%d: Stability/Scale: '%s' (expected log or linear)" % (path, line, s.scale))
    text, line = get("Bisections", "6")
    if not text.isdigit():
        raise StudyInputError("%s:%d: Stability/Bisections: expected a number, not '%s'" % (path, line, text))
    s.bisections = int(text)
    text, line = get("Monitor")
    s.monitor = _history_spec(text, path, line, "Monitor") if text else None   # none: completion (and balance) only
    text, line = get("Skip", "1")
    if not text.isdigit():
        raise StudyInputError("%s:%d: Stability/Skip: expected a number of steps, not '%s'" % (path, line, text))
    s.skip = int(text)
    text, line = get("Balance")
    s.balance = _history_spec(text, path, line, "Balance") if text else None
    text, line = get("Predicted")
    s.predicted = text     # expression of the ladder values: drawn and tabulated beside the measured limit
    if "Entries" not in node.children:
        raise StudyInputError("%s:%d: Stability needs 'subsection Entries' with the scene entries that use {%s}"
                              % (path, node.line, s.variable))
    s.entries = scene_entries(node.children["Entries"], path, "Stability/Entries")
    if not any("{" in v for _, v in s.entries):
        raise StudyInputError("%s:%d: Stability/Entries: no entry uses {%s}" % (path, node.line, s.variable))
    study.histories = [h for h in (s.monitor, s.balance) if h]
    return s


def verdict(record, stab):
    """(stable?, reason) of one trial."""
    if record["status"] != "completed":
        return False, "%s: %s" % (record["status"], record["reason"])
    if stab.monitor is None:
        return _balance_verdict(record, stab)
    h = record["histories"].get("%s:%s" % stab.monitor)
    if h is None:
        return False, "no column %s in %s" % (stab.monitor[1], stab.monitor[0])
    v = h[1]
    if any(not math.isfinite(x) for x in v):
        return False, "%s is not finite" % stab.monitor[1]
    d = [abs(v[i + 1] - v[i]) for i in range(len(v) - 1)]
    load, tail = d[:stab.skip] or [0.0], d[stab.skip:]
    scale = max(max(load), 1e-300)
    if len(tail) >= 3 and max(tail) > 1e-6 * scale:
        k = max(1, len(tail) // 3)
        first, last = sum(tail[:k]) / k, sum(tail[-k:]) / k
        if last > first:
            return False, "step changes of %s grow x%.3g over the run" % (stab.monitor[1], last / max(first, 1e-300))
    return _balance_verdict(record, stab)


def _balance_verdict(record, stab):
    if stab.balance:
        b = record["histories"].get("%s:%s" % stab.balance)
        if b is not None and len(b[1]) >= 4:
            half = len(b[1]) // 2
            a, z = max(abs(x) for x in b[1][:half]), max(abs(x) for x in b[1][half:])
            if z > 1e-6 and z > 10 * a:
                return False, "%s grows from %.2g to %.2g" % (stab.balance[1], a, z)
    return True, ""


def predicted_for(text, labels):
    """'expr' for every grid point, or 'level: expr; level: expr' per ladder level."""
    if ":" not in text:
        return text
    for part in text.split(";"):
        level, _, expr = part.partition(":")
        if level.strip() in labels:
            return expr.strip()
    return ""


def _mid(lo, hi, scale):
    return math.sqrt(lo * hi) if scale == "log" else 0.5 * (lo + hi)


def run_stability(study, stab, runner, cli_sets, out):
    points = []
    for levels in A.grid(study.ladders):
        variables = A.variables_of(study.ladders, levels)
        points.append({"levels": levels, "variables": variables, "lo": None, "hi": None, "trials": 0,
                       "state": "start", "reason": "",
                       "label": ", ".join("%s=%s" % (l.name, l.label(i)) for l, i in zip(study.ladders, levels))})

    def spec(p, x):
        var = dict(p["variables"], **{stab.variable: x})
        ov = [(k, A.substitute(v, var, "Set/" + k)) for k, v in study.sets]
        ov += A.overrides_of(study.ladders, p["levels"], var)
        ov += [(k, A.substitute(v, var, "Stability/Entries/" + k)) for k, v in stab.entries] + cli_sets
        return runner.spec(ov, "%s, %s=%.6g" % (p["label"], stab.variable, x))

    # Round 1: the top of the range; round 2: its bottom; then bisections.
    for rnd in range(2 + stab.bisections):
        active, xs = [], []
        for p in points:
            if p["state"] == "start":
                xs.append(stab.hi)
            elif p["state"] == "top unstable":
                xs.append(stab.lo)
            elif p["state"] == "bracket" and rnd < 2 + stab.bisections:
                xs.append(_mid(p["lo"], p["hi"], stab.scale))
            else:
                continue
            active.append(p)
        if not active:
            break
        records = runner.run_all([spec(p, x) for p, x in zip(active, xs)])
        for p, x, rec in zip(active, xs, records):
            ok, why = verdict(rec, stab)
            p["trials"] += 1
            if p["state"] == "start":
                p["state"], p["reason"] = ("stable over the range", "") if ok else ("top unstable", why)
                p["lo" if ok else "hi"] = x
            elif p["state"] == "top unstable":
                p["state"] = "bracket" if ok else "unstable over the range"
                if ok:
                    p["lo"] = x
                else:
                    p["hi"], p["reason"] = x, why
            else:
                if ok:
                    p["lo"] = x
                else:
                    p["hi"], p["reason"] = x, why
    for p in points:
        if p["state"] == "bracket":
            p["state"] = "limit"
        p["predicted"] = None
        if stab.predicted:
            expr = predicted_for(stab.predicted, [l.label(i) for l, i in zip(study.ladders, p["levels"])])
            try:
                p["predicted"] = A.evaluate(expr, p["variables"], "Stability/Predicted") if expr else None
            except ValueError:
                p["predicted"] = None
    write_stability(study, stab, points, out)
    return points


def write_stability(study, stab, points, out):
    head = [l.name for l in study.ladders] + ["state", "largest_stable_" + stab.variable,
                                              "smallest_unstable_" + stab.variable, "estimate", "predicted",
                                              "trials", "reason"]
    with open(os.path.join(out, "stability.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(head)
        for p in points:
            est = _mid(p["lo"], p["hi"], stab.scale) if p["state"] == "limit" else None
            p["estimate"] = est
            w.writerow([l.label(i) for l, i in zip(study.ladders, p["levels"])] +
                       [p["state"], "%.6g" % p["lo"] if p["lo"] is not None else "",
                        "%.6g" % p["hi"] if p["hi"] is not None else "", "%.6g" % est if est else "",
                        "%.6g" % p["predicted"] if p["predicted"] is not None else "", p["trials"], p["reason"]])
    L = ["# Stability map %s" % study.name, "",
         "Largest %s in [%g, %g] at which the run stays stable (bisection, %d steps, %s scale); %s%s."
         % (stab.variable, stab.lo, stab.hi, stab.bisections, stab.scale,
            ("monitored: %s in %s" % (stab.monitor[1], stab.monitor[0])) if stab.monitor else "the run must complete",
            (", balance: %s" % stab.balance[1]) if stab.balance else ""), "",
         "| " + " | ".join([l.name for l in study.ladders] + ["result", "largest stable", "first unstable",
                                                              "predicted", "why unstable"]) + " |",
         "|" + "---|" * (len(study.ladders) + 5)]
    for p in points:
        L.append("| " + " | ".join([l.label(i) for l, i in zip(study.ladders, p["levels"])] +
                                   [p["state"], "%.4g" % p["lo"] if p["lo"] is not None else "—",
                                    "%.4g" % p["hi"] if p["hi"] is not None else "—",
                                    "%.4g" % p["predicted"] if p["predicted"] is not None else "—",
                                    p["reason"] or "—"]) + " |")
    with open(os.path.join(out, "stability.md"), "w") as f:
        f.write("\n".join(L) + "\n")
    plot_stability(study, stab, points, os.path.join(out, "stability.png"))


def plot_stability(study, stab, points, path):
    from .report import _pyplot
    plt = _pyplot()
    if plt is None:
        return
    schemes = [k for k, l in enumerate(study.ladders) if l.role == "scheme"]
    axis = [k for k, l in enumerate(study.ladders) if l.role != "scheme" and l.values is not None]
    fig, ax = plt.subplots(figsize=(7, 5))
    groups = {}
    for p in points:
        key = ", ".join(study.ladders[k].label(p["levels"][k]) for k in schemes) or "runs"
        groups.setdefault(key, []).append(p)
    # Schemes without a limit all sit at the range's end: side by side, not
    # hidden behind each other.
    at_end = [key for key, members in groups.items() if any(p["state"] != "limit" for p in members)]
    log_x = bool(axis) and all(v > 0 for v in study.ladders[axis[0]].values)

    def beside(x, key):
        k = at_end.index(key) - (len(at_end) - 1) / 2
        return x * 1.15 ** k if log_x else x + 0.08 * k

    for n, (key, members) in enumerate(groups.items()):
        xs = [study.ladders[axis[0]].values[p["levels"][axis[0]]] if axis else n for p in members]
        color = "C%d" % n
        for x, p in zip(xs, members):
            if p["state"] == "limit":
                ax.plot([x, x], [p["lo"], p["hi"]], "-", color=color, lw=3)
            elif p["state"] == "stable over the range":
                ax.plot(beside(x, key), stab.hi, "^", color=color, ms=10)
            else:
                ax.plot(beside(x, key), stab.lo, "v", color=color, ms=10)
        lim = [(x, p["estimate"]) for x, p in zip(xs, members) if p["state"] == "limit"]
        if lim:
            ax.plot([q[0] for q in lim], [q[1] for q in lim], "o-", color=color, label=key + ": limit")
        for state, marker, text in (("stable over the range", "^", "stable up to the top of the range"),
                                    ("unstable over the range", "v", "unstable at the bottom of the range")):
            if any(p["state"] == state for p in members):
                ax.plot([], [], marker, color=color, label=key + ": " + text)
        pred = [(x, p["predicted"]) for x, p in zip(xs, members) if p["predicted"] is not None]
        if pred:
            ax.plot([q[0] for q in pred], [q[1] for q in pred], "x:", color=color, ms=12, label=key + ": predicted")
    ax.axhline(stab.hi, color="grey", lw=0.5)
    ax.axhline(stab.lo, color="grey", lw=0.5)
    if stab.scale == "log":
        ax.set_yscale("log")
    if axis:
        ax.set_xlabel(study.ladders[axis[0]].name)
        if all(v > 0 for v in study.ladders[axis[0]].values):
            ax.set_xscale("log")
    else:
        ax.set_xticks(range(len(groups)))
        ax.set_xticklabels(list(groups), fontsize=8)
    ax.set_ylabel("largest stable %s" % stab.variable)
    ax.set_title("%s: stability limit (bars: bisection bracket)" % study.name)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)

"""What each physics costs: the scene as it is (the baseline) and with one
physics switched off per variant (subsection Physics cost of the study):
the wall time of each and the change of each quantity against the baseline,
so a user sees what a simplification buys and what it costs in accuracy."""
import csv
import math
import os

from . import analysis as A


def run_physics_cost(study, runner, cli_sets, out):
    base = [(k, A.substitute(v, {}, "Set/" + k)) for k, v in study.sets]
    variants = [("baseline (the scene)", [])] + study.variants
    specs = [runner.spec(base + list(entries) + cli_sets, name) for name, entries in variants]
    records = runner.run_all(specs)
    rows = []
    for (name, entries), rec in zip(variants, records):
        values = {q.name: (A.quantity_value(rec, q) if rec["status"] == "completed" else None)
                  for q in study.quantities}
        rows.append({"name": name, "entries": entries, "record": rec, "values": values,
                     "wall": A.median(rec["wall_times"])})
    ref = rows[0]
    for row in rows:
        row["changes"] = {}
        for q in study.quantities:
            v, r = row["values"][q.name], ref["values"][q.name]
            if v is None or r is None:
                row["changes"][q.name] = None
            elif q.kind == "summary":
                row["changes"][q.name] = (v - r, A.scalar_error(v, r, True))
            else:
                row["changes"][q.name] = (None, A.history_error(v, r, True))
    write(study, rows, out)
    return rows


def _num(v):
    return "" if v is None else ("%.17g" % v if isinstance(v, float) else str(v))


def write(study, rows, out):
    head = ["variant", "status", "reason", "wall_time_median [s]", "wall_time_ratio"]
    for q in study.quantities:
        head += [q.name, "change_" + q.name, "relative_change_" + q.name]
    head += ["steps", "newton_iterations", "entries"]
    base_wall = rows[0]["wall"] or float("nan")
    with open(os.path.join(out, "physics_cost.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(head)
        for r in rows:
            rec = r["record"]
            line = [r["name"], rec["status"], rec["reason"], _num(r["wall"]), _num(r["wall"] / base_wall)]
            for q in study.quantities:
                v, c = r["values"][q.name], r["changes"][q.name]
                line += ["history" if isinstance(v, tuple) else _num(v), _num(c[0]) if c else "",
                         _num(c[1]) if c else ""]
            line += [_num(rec["summary"].get("steps")), _num(rec["summary"].get("newton_iterations")),
                     "; ".join("%s=%s" % e for e in r["entries"])]
            w.writerow(line)
    L = ["# Physics cost: %s" % study.name, "",
         "The scene, then the scene with one physics switched off per row; wall time (median of %d) and the "
         "change of each quantity against the scene as it is (histories: relative L2 in time)." % study.repeats, "",
         "| variant | switched off by | wall (s) | x scene | " + " | ".join(q.name for q in study.quantities) +
         " | status |", "|" + "---|" * (5 + len(study.quantities))]
    for r in rows:
        cells = [r["name"], "; ".join("`%s = %s`" % e for e in r["entries"]) or "—", "%.2f" % r["wall"],
                 "%.2f" % (r["wall"] / base_wall) if math.isfinite(base_wall) else "—"]
        for q in study.quantities:
            v, c = r["values"][q.name], r["changes"][q.name]
            if v is None:
                cells.append("—")
            elif r is rows[0]:
                cells.append("history" if isinstance(v, tuple) else "%.6g" % v)
            elif isinstance(v, tuple):
                cells.append("%.3g %%" % (100 * c[1]))
            else:
                cells.append("%.6g (%+.3g %%)" % (v, 100 * c[1] * (1 if c[0] >= 0 else -1)))
        rec = r["record"]
        cells.append(rec["status"] + ((": " + rec["reason"]) if rec["reason"] else ""))
        L.append("| " + " | ".join(cells) + " |")
    with open(os.path.join(out, "physics_cost.md"), "w") as f:
        f.write("\n".join(L) + "\n")

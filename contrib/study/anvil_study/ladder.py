"""A ladder study: every combination of the ladders' levels is one run; each
run's quantities are compared with the reference (closed form, the finest
run of its group, or a separate reference run)."""
import math

from . import analysis as A

COSTS = (("steps", "steps"), ("cut_backs", "cut_backs"), ("newton_iterations", "newton_iterations"),
         ("linear_iterations", "linear_iterations"), ("arkode_steps", "heat.arkode_internal_steps"),
         ("arkode_nonlinear_iterations", "heat.arkode_nonlinear_iterations"),
         ("staggered_iterations", "heat.staggered_iterations"), ("peak_memory_MB", "peak_memory_MB"))


def convergence_ladders(study):
    return [i for i, l in enumerate(study.ladders) if l.role in ("time step", "mesh size")]


def plan(study, runner, cli_sets):
    """The specs of the study's runs (and of its reference run), in order."""
    specs = []
    for levels in A.grid(study.ladders):
        variables = A.variables_of(study.ladders, levels)
        base = [(p, A.substitute(v, variables, "Set/" + p)) for p, v in study.sets]
        ov = base + A.overrides_of(study.ladders, levels, variables) + cli_sets
        label = ", ".join("%s=%s" % (l.name, l.label(i)) for l, i in zip(study.ladders, levels))
        specs.append(dict(runner.spec(ov, label), levels=levels, variables=variables))
    ref = None
    if study.reference_type == "run":
        ov = list(study.sets) + list(study.reference_run) + cli_sets
        ref = dict(runner.spec(ov, "reference run"), levels=None, variables={})
    return specs, ref


def group_key(study, levels, skip):
    return tuple(i for k, i in enumerate(levels) if k not in skip)


def group_label(study, levels, skip):
    parts = ["%s=%s" % (l.name, l.label(i)) for k, (l, i) in enumerate(zip(study.ladders, levels)) if k not in skip]
    return ", ".join(parts) or "all runs"


def evaluate_runs(study, specs, records, ref_record):
    """Rows of the table: settings, quantities, errors, cost, status."""
    conv = convergence_ladders(study)
    relative = study.error_kind == "relative"
    rows = []
    for spec, rec in zip(specs, records):
        row = {"spec": spec, "record": rec, "status": rec["status"], "reason": rec["reason"], "values": {},
               "errors": {}, "is_reference": False}
        walls = rec["wall_times"]
        row["wall"] = A.median(walls)
        row["spread"] = (max(walls) - min(walls)) / row["wall"] if row["wall"] > 0 and len(walls) > 1 else 0.0
        row["costs"] = {name: A.summary_value(rec.get("summary", {}), key) for name, key in COSTS}
        for q in study.quantities:
            row["values"][q.name] = A.quantity_value(rec, q) if rec["status"] == "completed" else None
        bad = [n for n, v in row["values"].items() if isinstance(v, float) and not math.isfinite(v)]
        if rec["status"] == "completed" and bad:
            row["status"], row["reason"] = "unstable", "not finite: " + ", ".join(bad)
        elif rec["status"] == "completed" and any(v is None for v in row["values"].values()):
            missing = [q.name for q in study.quantities if row["values"][q.name] is None]
            row["status"], row["reason"] = "error", "quantity not in the run's output: " + ", ".join(missing)
        rows.append(row)
    # Reference values per row.
    finest = {}
    if study.reference_type == "finest":
        last = tuple(len(study.ladders[k]) - 1 for k in conv)
        for row in rows:
            lv = row["spec"]["levels"]
            if tuple(lv[k] for k in conv) == last:
                finest[group_key(study, lv, conv)] = row
                row["is_reference"] = True
    if ref_record is not None:
        for row in rows:    # the reference run is also a run of the ladders
            row["is_reference"] = row["record"]["key"] == ref_record["key"]
    for row in rows:
        for q in study.quantities:
            row["errors"][q.name] = float("nan")
            value = row["values"][q.name]
            if value is None:
                continue
            try:
                if study.reference_type == "closed form":
                    ref = A.closed_form_reference(q, study.reference_values[q.name][0],
                                                  row["spec"]["variables"], value)
                elif study.reference_type == "finest":
                    r = finest.get(group_key(study, row["spec"]["levels"], conv))
                    ref = r["values"][q.name] if r and r["status"] == "completed" else None
                else:
                    ref = A.quantity_value(ref_record, q) if ref_record and ref_record["status"] == "completed" \
                        else None
            except ValueError as e:
                row["status"], row["reason"] = "error", str(e)
                continue
            if ref is None:
                continue
            if q.kind == "summary":
                row["errors"][q.name] = A.scalar_error(value, ref, relative)
            else:
                row["errors"][q.name] = A.history_error(value, ref, relative)
        errs = list(row["errors"].values())
        if study.accuracy_quantity:
            row["error"] = row["errors"][study.accuracy_quantity]
        else:
            row["error"] = max(errs) if errs and all(math.isfinite(e) for e in errs) else float("nan")
    return rows


def orders(study, rows):
    """Observed orders along each Δt / h ladder, per group of the others."""
    out = []
    for c in convergence_ladders(study):
        ladder = study.ladders[c]
        groups = {}
        for row in rows:
            lv = row["spec"]["levels"]
            groups.setdefault(group_key(study, lv, [c]), []).append(row)
        for key, members in groups.items():
            members.sort(key=lambda r: r["spec"]["levels"][c])
            label = group_label(study, members[0]["spec"]["levels"], [c])
            for q in study.quantities + [None]:
                xs, es = [], []
                for r in members:
                    e = r["error"] if q is None else r["errors"][q.name]
                    if r["status"] == "completed" and not r["is_reference"] and math.isfinite(e) and e > 0:
                        xs.append(ladder.values[r["spec"]["levels"][c]])
                        es.append(e)
                last = None
                if len(xs) >= 2:
                    last = math.log(es[-2] / es[-1]) / math.log(xs[-2] / xs[-1])
                out.append({"ladder": ladder.name, "role": ladder.role, "group": label,
                            "quantity": q.name if q else "error", "x": xs, "e": es,
                            "order_fit": A.fit_order(xs, es), "order_last": last})
    return out


def curves(study, rows):
    """Work-precision curves: one per combination of the non-Δt/h ladders."""
    conv = convergence_ladders(study)
    out = {}
    for row in rows:
        lv = row["spec"]["levels"]
        out.setdefault(group_label(study, lv, conv), []).append(row)
    return out

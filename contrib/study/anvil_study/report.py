"""What a ladder study writes: study.csv, study.md, work_precision.png,
convergence.png. The table is a function of the run records only (no clock
of its own), so a study restarted from its records writes the same table."""
import csv
import math
import os

from . import analysis as A
from .ladder import COSTS, convergence_ladders, curves


def fmt(v):
    if v is None:
        return ""
    if isinstance(v, float):
        return "nan" if math.isnan(v) else "%.17g" % v
    return str(v)


def write_csv(study, rows, path):
    head = ["run"] + [l.name for l in study.ladders]
    for q in study.quantities:
        head += [q.name, "error_" + q.name]
    head += ["error", "wall_time_median [s]", "wall_time_spread", "repeats"] + [c for c, _ in COSTS]
    head += ["status", "reason", "key", "settings"]
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(head)
        for n, row in enumerate(rows):
            lv = row["spec"]["levels"]
            line = [n] + [l.label(i) for l, i in zip(study.ladders, lv)]
            for q in study.quantities:
                v = row["values"][q.name]
                line += [fmt(v) if not isinstance(v, tuple) else "history", fmt(row["errors"][q.name])]
            line += [fmt(row["error"]), fmt(row["wall"]), fmt(row["spread"]), len(row["record"]["wall_times"])]
            line += [fmt(row["costs"][c]) for c, _ in COSTS]
            ladder_paths = {p for l in study.ladders for p, _ in l.entries}
            line += [row["status"], row["reason"], row["spec"]["key"],
                     "; ".join("%s=%s" % (p, v) for p, v in row["spec"]["overrides"] if p in ladder_paths)]
            w.writerow(line)


RELATIVE = [True]   # set by summary_lines: relative errors print as percentages


def _pct(e):
    if e is None or not math.isfinite(e):
        return "—"
    return ("%.3g %%" % (100 * e) if e >= 1e-4 else "%.2e" % e) if RELATIVE[0] else "%.3g" % e


def summary_lines(study, rows, order_list):
    """study.md: the table, orders, Pareto set, cheapest run per accuracy level, failures."""
    RELATIVE[0] = study.error_kind == "relative"
    ok = [r for r in rows if r["status"] == "completed" and math.isfinite(r["error"]) and not r["is_reference"]]
    what = ("the error of %s" % study.accuracy_quantity) if study.accuracy_quantity else \
        "the largest error over the quantities"
    L = ["# Study %s" % study.name, "",
         "Scene `%s`; %d runs (%s); reference: %s; error: %s %s; wall time: median of %d repeat(s)."
         % (os.path.relpath(study.scene, os.path.dirname(os.path.abspath(study.path))), len(rows), " x ".join("%s (%d)" % (l.name, len(l)) for l in study.ladders),
            study.reference_type, study.error_kind, what, study.repeats), ""]
    head = [l.name for l in study.ladders] + [q.name for q in study.quantities] + \
        ["error", "wall (s)", "steps", "Newton", "status"]
    L += ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    for r in rows:
        lv = r["spec"]["levels"]
        cells = [l.label(i) for l, i in zip(study.ladders, lv)]
        for q in study.quantities:
            v = r["values"][q.name]
            cells.append("history" if isinstance(v, tuple) else ("%.6g" % v if v is not None else "—"))
        cells += ["reference" if r["is_reference"] else _pct(r["error"]), "%.2f" % r["wall"],
                  fmt(r["costs"]["steps"]), fmt(r["costs"]["newton_iterations"]),
                  r["status"] + ((": " + r["reason"]) if r["reason"] else "")]
        L.append("| " + " | ".join(cells) + " |")
    if order_list:
        L += ["", "## Observed orders", "",
              "Least-squares slope of log(error) against log(%s) over the runs of each group, and the slope "
              "of its last two runs." % "/".join(sorted({o["ladder"] for o in order_list})), "",
              "| ladder | group | quantity | errors | fitted order | last two |", "|---|---|---|---|---|---|"]
        for o in order_list:
            if o["order_fit"] is None or (o["quantity"] == "error" and len(study.quantities) == 1):
                continue
            L.append("| %s | %s | %s | %s | %.3f | %.3f |" % (o["ladder"], o["group"], o["quantity"],
                     " ".join("%.3g" % e for e in o["e"]), o["order_fit"], o["order_last"]))
    pts = [(r["wall"], r["error"]) for r in ok]
    front = [ok[i] for i in A.pareto(pts)]
    L += ["", "## Pareto set (no other run is both cheaper and more accurate)", ""]
    L += ["- %s: error %s in %.2f s" % (r["spec"]["label"], _pct(r["error"]), r["wall"]) for r in front] or ["- none"]
    L += ["", "## Cheapest run under each accuracy level", "", "| error below | cheapest run | its error | wall (s) |",
          "|---|---|---|---|"]
    for level in study.accuracy_levels:
        good = [r for r in ok if r["error"] <= level]
        if good:
            best = min(good, key=lambda r: r["wall"])
            L.append("| %s | %s | %s | %.2f |" % (_pct(level), best["spec"]["label"], _pct(best["error"]), best["wall"]))
        else:
            L.append("| %s | none of the runs reached it | | |" % _pct(level))
    bad = [r for r in rows if r["status"] != "completed"]
    L += ["", "## Runs that did not complete", ""]
    L += ["- %s: %s — %s (run folder runs/%s)" % (r["spec"]["label"], r["status"], r["reason"], r["spec"]["key"])
          for r in bad] or ["- none: every run completed."]
    return L


def _pyplot():
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        return plt
    except ImportError:
        print("anvil-study: note: matplotlib is missing (apt-get install python3-matplotlib): no figures written")
        return None


def _plain_ticks(ax):
    """Readable wall-time ticks when the runs span less than a decade."""
    from matplotlib.ticker import NullFormatter, ScalarFormatter
    lo, hi = ax.get_xlim()
    if hi < 10 * lo:
        ax.xaxis.set_minor_formatter(NullFormatter())
        ax.xaxis.set_major_formatter(ScalarFormatter())
        ax.set_xticks([lo * (hi / lo) ** (k / 4) for k in range(5)])
        ax.set_xticklabels(["%.3g" % (lo * (hi / lo) ** (k / 4)) for k in range(5)])


def plot_work_precision(study, rows, path):
    plt = _pyplot()
    if plt is None:
        return
    fig, ax = plt.subplots(figsize=(7, 5))
    ok = [r for r in rows if r["status"] == "completed" and math.isfinite(r["error"]) and r["error"] > 0
          and not r["is_reference"]]
    for label, members in curves(study, rows).items():
        pts = [(r["wall"], r["error"]) for r in members if r in ok]    # in ladder order (one axis)
        if len(convergence_ladders(study)) > 1:
            pts.sort()    # Δt and h together: by cost
        if pts:
            ax.plot([p[0] for p in pts], [p[1] for p in pts], "o-", label=label)
    front = [ok[i] for i in A.pareto([(r["wall"], r["error"]) for r in ok])]
    if front:
        ax.plot([r["wall"] for r in front], [r["error"] for r in front], "k--", lw=1, zorder=0)
        ax.plot([r["wall"] for r in front], [r["error"] for r in front], "s", mfc="none", mec="k", ms=11,
                label="Pareto front")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("wall time per run (s, median of %d)" % study.repeats)
    _plain_ticks(ax)
    ax.set_ylabel(("%s error of %s" % (study.error_kind, study.accuracy_quantity)) if study.accuracy_quantity
                  else "%s error (largest over the quantities)" % study.error_kind)
    ax.set_title("%s: work against precision" % study.name)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def plot_convergence(study, order_list, path):
    plt = _pyplot()
    if plt is None:
        return
    names = [study.ladders[c].name for c in convergence_ladders(study)]
    if not names:
        return
    fig, axes = plt.subplots(1, len(names), figsize=(6.5 * len(names), 5), squeeze=False)
    for ax, name in zip(axes[0], names):
        ladder = next(l for l in study.ladders if l.name == name)
        for o in order_list:
            if o["ladder"] != name or o["order_fit"] is None:
                continue
            if o["quantity"] != "error" and len(study.quantities) > 1 and not study.accuracy_quantity:
                continue    # one curve per group: the error the study ranks by
            if o["quantity"] == "error" and len(study.quantities) == 1:
                continue
            ax.loglog(o["x"], o["e"], "o-", label="%s%s: order %.2f" % (o["group"],
                      "" if o["quantity"] == "error" else " (%s)" % o["quantity"], o["order_fit"]))
        ax.set_xlabel("%s (%s)" % (name, ladder.role))
        ax.set_ylabel("%s error" % study.error_kind)
        ax.set_title("%s: error against %s, fitted orders" % (study.name, name))
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)

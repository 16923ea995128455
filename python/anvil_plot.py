#!/usr/bin/python3
"""anvil-plot: plot any history column of anvil runs against another.

    anvil-plot RUN [RUN ...] -x time -y upper.top_Fx [-y ...] -o force.png
    anvil-plot output/a output/b -x upper.top_ux -y upper.top_Fx -o fd.pdf --label a --label b
    anvil-plot RUN --list                       # every column of every CSV, with its unit
    anvil-plot RUN --figures 'name: x -> y1, y2; name2: field temperature at 1e-3'

A RUN is an output directory (the column is looked up in its CSV files:
reactions, probes, energy, contact, thermal, newton) or one CSV file. A
column is named as in the CSV header, with or without its " [unit]"; prefix
it with a file to choose among files that share a name (energy.csv:time).
Several runs are overlaid (one line per run and column); axes are labelled
with the columns' units. The suffix of -o chooses PNG or PDF.

--figures writes a scene's standard figures (Output/Figure list) into
RUN/figures/<name>.png: 'name: X -> Y[, Y...]' is a history plot,
'name: field F [at TIME] [undeformed]' a field on the deformed mesh drawn
by anvil-render (the last output time by default).

Runs with Debian's /usr/bin/python3 (python3-matplotlib); a python3 from
pyenv or a venv does not see Debian's packages.
"""
import argparse
import csv
import glob
import os
import subprocess
import sys

# The order in which a run's files are searched for a column: the physical
# histories first, so that 'time' comes from reactions.csv and not newton.csv.
FILE_ORDER = ["reactions.csv", "probes.csv", "energy.csv", "contact.csv", "thermal.csv",
              "newton.csv"]


def fail(message):
    """One line naming what was expected, exit 2 (the house rule for bad input)."""
    sys.stderr.write("anvil-plot: error: %s\n" % message)
    sys.exit(2)


def bare(name):
    """'reaction_x [N]' -> 'reaction_x': the name a column is matched by."""
    return name.split(" [", 1)[0].strip()


def unit(name):
    """'reaction_x [N]' -> 'N'; '' when the header carries no unit."""
    return name.split(" [", 1)[1].rstrip("]").strip() if " [" in name else ""


class Table:
    """One CSV history: columns by bare name, their headers with units."""

    def __init__(self, path):
        self.path = path
        with open(path) as f:
            rows = list(csv.reader(f))
        if not rows:
            fail("%s is empty (no header)" % path)
        self.headers = {bare(h): h for h in rows[0]}
        self.columns = {bare(h): [float(r[i]) if r[i] not in ("", "nan") else float("nan")
                                  for r in rows[1:]] for i, h in enumerate(rows[0])}

    def has(self, name):
        return bare(name) in self.columns


def run_files(run):
    """The CSV histories of a run (a directory) in search order, or the file itself."""
    if os.path.isfile(run):
        return [run]
    if not os.path.isdir(run):
        fail("run '%s' is neither an output directory nor a CSV file" % run)
    found = sorted(glob.glob(os.path.join(run, "*.csv")))
    order = {n: i for i, n in enumerate(FILE_ORDER)}
    return sorted(found, key=lambda p: (order.get(os.path.basename(p), len(order)), p))


def lookup(run, column, other=None, cache={}):
    """(table, name) of the first table of @p run that holds @p column (and
    @p other, so that both come from the same rows), or None; 'file.csv:name'
    chooses the file."""
    wanted_file = None
    if ":" in column and column.split(":", 1)[0].endswith(".csv"):
        wanted_file, column = column.split(":", 1)
    for path in run_files(run):
        if wanted_file and os.path.basename(path) != wanted_file:
            continue
        if path not in cache:
            cache[path] = Table(path)
        t = cache[path]
        if t.has(column) and (other is None or t.has(other.split(":")[-1])):
            return t, column
    return None


def find_table(run, column):
    found = lookup(run, column)
    if found is None:
        names = sorted({c for p in run_files(run) for c in Table(p).columns})
        fail("run '%s' has no column '%s' (columns: %s)" % (run, column, ", ".join(names)))
    return found


def paired(run, x, y):
    """x and y values of the same steps, and their axis labels: from one file
    when it has both, else from two, matched on their time column
    (reactions.csv's force against probes.csv's displacement)."""
    both = lookup(run, y, x)
    if both is not None:
        t, ycol = both
        xcol = x.split(":")[-1]
        return t.columns[bare(xcol)], t.columns[bare(ycol)], axis_label(t, xcol), axis_label(t, ycol)
    ty, ycol = find_table(run, y)
    tx, xcol = find_table(run, x)
    if not (ty.has("time") and tx.has("time")):
        fail("run '%s': '%s' and '%s' are in files without a time column to match" % (run, x, y))
    at = dict(zip(tx.columns["time"], tx.columns[bare(xcol)]))
    rows = [(at[t], v) for t, v in zip(ty.columns["time"], ty.columns[bare(ycol)]) if t in at]
    return [r[0] for r in rows], [r[1] for r in rows], axis_label(tx, xcol), axis_label(ty, ycol)


def axis_label(table, column):
    header = table.headers[bare(column)]
    return "%s [%s]" % (bare(header), unit(header)) if unit(header) else bare(header)


def plot(runs, x, ys, output, labels=None, title=None, logy=False):
    """Overlays y(x) of every run; writes PNG or PDF by @p output's suffix."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    if not output.lower().endswith((".png", ".pdf")):
        fail("output '%s': expected a .png or .pdf file" % output)
    if labels and len(labels) != len(runs):
        fail("%d --label for %d runs: give one per run or none" % (len(labels), len(runs)))
    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    ylabels = []
    for k, run in enumerate(runs):
        name = labels[k] if labels else os.path.basename(os.path.normpath(run))
        for y in ys:
            xs, yv, xlabel, ylabel = paired(run, x, y)
            ylabels.append(ylabel)
            line = name if len(ys) == 1 else (bare(y) if len(runs) == 1 else
                                              "%s: %s" % (name, bare(y)))
            # Dashes after the first curve: equal curves (a balance) stay visible.
            style = ["-", "--", ":", "-."][len(ylabels) - 1 if len(runs) == 1 else k % 4]
            ax.plot(xs, yv, style, marker="." if len(xs) < 40 else None, label=line)
    ax.set_xlabel(xlabel)
    # One unit for all the curves: "a, b [N]"; else each with its own.
    names = list(dict.fromkeys(l.split(" [")[0] for l in ylabels))
    units = list(dict.fromkeys(l.split(" [", 1)[1] for l in ylabels if " [" in l))
    if len(units) == 1 and all(" [" in l for l in ylabels):
        ax.set_ylabel("%s [%s" % (", ".join(names), units[0]))
    else:
        ax.set_ylabel(", ".join(dict.fromkeys(ylabels)))
    if logy:
        ax.set_yscale("log")
    if len(runs) > 1 or len(ys) > 1:
        ax.legend()
    ax.grid(True, alpha=0.3)
    ax.set_title(title or ", ".join(os.path.basename(os.path.normpath(r)) for r in runs))
    fig.tight_layout()
    os.makedirs(os.path.dirname(os.path.abspath(output)), exist_ok=True)
    fig.savefig(output, dpi=120)
    plt.close(fig)


def parse_figures(spec):
    """'name: x -> y1, y2; name2: field F [at T] [undeformed]' -> list of dicts."""
    figures = []
    for item in [i.strip() for i in spec.split(";") if i.strip()]:
        if ":" not in item:
            fail("figure '%s': expected 'name: x -> y' or 'name: field F [at time]'" % item)
        name, body = [s.strip() for s in item.split(":", 1)]
        if body.startswith("field "):
            words = body.split()
            fig = {"name": name, "kind": "field", "field": words[1], "time": None,
                   "deformed": "undeformed" not in words}
            if "at" in words:
                fig["time"] = words[words.index("at") + 1]
            figures.append(fig)
        elif "->" in body:
            x, y = body.split("->", 1)
            figures.append({"name": name, "kind": "history", "x": x.strip(),
                            "y": [c.strip() for c in y.split(",") if c.strip()]})
        else:
            fail("figure '%s': expected 'name: x -> y[, y...]' or 'name: field F [at time]'" % item)
    return figures


def write_figures(run, spec):
    """A scene's standard figures into RUN/figures; returns the files written."""
    written = []
    for f in parse_figures(spec):
        out = os.path.join(run, "figures", f["name"] + ".png")
        if f["kind"] == "history":
            plot([run], f["x"], f["y"], out, title=f["name"].replace("_", " "))
        else:
            render = os.path.join(os.path.dirname(os.path.realpath(__file__)), "anvil-render")
            if not os.path.exists(render):
                render = os.path.join(os.path.dirname(os.path.realpath(__file__)), "anvil_render.py")
            cmd = ["/usr/bin/python3", render, run, "--field", f["field"], "-o", out]
            if f["time"] is not None:
                cmd += ["--time", f["time"]]
            if not f["deformed"]:
                cmd += ["--undeformed"]
            status = subprocess.call(cmd)
            if status != 0:
                sys.exit(status)
        written.append(out)
    return written


def main():
    p = argparse.ArgumentParser(prog="anvil-plot", description=__doc__.split("\n\n")[0],
                                formatter_class=argparse.RawDescriptionHelpFormatter,
                                epilog=__doc__.split("\n\n", 1)[1])
    p.add_argument("runs", nargs="+", help="output directories or CSV files")
    p.add_argument("-x", default="time", help="column on the horizontal axis (default: time)")
    p.add_argument("-y", action="append", default=[], help="column(s) on the vertical axis")
    p.add_argument("-o", "--output", help="figure file, .png or .pdf")
    p.add_argument("--label", action="append", help="legend entry per run (default: its name)")
    p.add_argument("--title")
    p.add_argument("--logy", action="store_true", help="logarithmic vertical axis")
    p.add_argument("--list", action="store_true", help="print every column of each run")
    p.add_argument("--figures", metavar="SPEC", help="write a scene's figure list into RUN/figures")
    a = p.parse_args()
    if a.list:
        for run in a.runs:
            for path in run_files(run):
                print("%s: %s" % (os.path.basename(path), ", ".join(Table(path).headers.values())))
        return
    if a.figures is not None:
        for run in a.runs:
            for f in write_figures(run, a.figures):
                print(f)
        return
    if not a.y or not a.output:
        fail("expected -y COLUMN and -o FILE.png|pdf (or --list, --figures)")
    plot(a.runs, a.x, a.y, a.output, a.label, a.title, a.logy)
    print(a.output)


if __name__ == "__main__":
    main()

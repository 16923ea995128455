"""From runs to answers: the quantities of each run, their errors against the
reference, the observed orders along the Δt and h ladders, the Pareto set of
error against wall time and the cheapest run under each accuracy level.
"""
import itertools
import math
import re

from .runner import strip_unit

MATH = {k: getattr(math, k) for k in dir(math) if not k.startswith("_")}


def evaluate(expr, variables, what):
    """A Python arithmetic expression (math functions, the ladder values by
    ladder name, t for histories); raises ValueError with a readable text."""
    try:
        return float(eval(expr, dict(MATH, __builtins__={}, **variables)))
    except Exception as e:   # any error of the user's expression
        raise ValueError("%s: cannot evaluate '%s' (%s)" % (what, expr, e))


def substitute(value, variables, what):
    """Scene values may hold {expression}: replaced by its value (%.15g)."""
    def one(m):
        return "%.15g" % evaluate(m.group(1), variables, what)
    return re.sub(r"\{([^{}]+)\}", one, value)


def variables_of(ladders, levels):
    """Ladder values by name (ladder names that are identifiers)."""
    out = {}
    for ladder, i in zip(ladders, levels):
        if ladder.values is not None and ladder.name.isidentifier():
            out[ladder.name] = ladder.values[i]
    return out


def grid(ladders):
    """Every combination of ladder levels (crossed), in ladder order."""
    return list(itertools.product(*[range(len(l)) for l in ladders]))


def overrides_of(ladders, levels, variables, extra=()):
    out = []
    for ladder, i in zip(ladders, levels):
        for path, value in ladder.overrides(i):
            out.append((path, substitute(value, variables, "ladder '%s', %s" % (ladder.name, path))))
    return out + list(extra)


def summary_value(summary, key):
    """A quantity of interest by name (before ' ['), else a dotted path."""
    qoi = {strip_unit(k): v for k, v in summary.get("quantities_of_interest", {}).items()}
    if strip_unit(key) in qoi:
        return qoi[strip_unit(key)]
    node = summary
    for part in key.split("."):
        if not isinstance(node, dict):
            return None
        node = {strip_unit(k): v for k, v in node.items()}.get(strip_unit(part))
    return node if isinstance(node, (int, float)) else None


def quantity_value(record, q):
    """Scalar (summary) or (times, values) (history); None if missing."""
    if q.kind == "summary":
        v = summary_value(record.get("summary", {}), q.key)
        return None if v is None else float(v)
    h = record.get("histories", {}).get("%s:%s" % (q.file, q.key))
    return None if h is None else (h[0], h[1])


def _trapezoid(t, f):
    return sum(0.5 * (t[i + 1] - t[i]) * (f[i + 1] + f[i]) for i in range(len(t) - 1))


def _interp(t, ts, fs):
    if t <= ts[0]:
        return fs[0]
    for i in range(len(ts) - 1):
        if ts[i] <= t <= ts[i + 1]:
            w = (t - ts[i]) / (ts[i + 1] - ts[i]) if ts[i + 1] > ts[i] else 0.0
            return fs[i] + w * (fs[i + 1] - fs[i])
    return fs[-1]


def history_error(run, ref, relative):
    """L2 in time: sqrt(int (q - r)^2 dt) over the reference's times (the run
    interpolated linearly), divided by sqrt(int r^2 dt) if relative."""
    (tr, fr), (tq, fq) = ref, run
    keep = [i for i, t in enumerate(tr) if t <= tq[-1] * (1 + 1e-12)]
    if len(keep) < 2:
        return float("nan")
    t = [tr[i] for i in keep]
    diff = [(_interp(x, tq, fq) - fr[i]) ** 2 for x, i in zip(t, keep)]
    num = math.sqrt(max(_trapezoid(t, diff), 0.0))
    if not relative:
        return num
    den = math.sqrt(_trapezoid(t, [fr[i] ** 2 for i in keep]))
    return num / den if den > 0 else float("nan")


def scalar_error(value, ref, relative):
    if relative and ref != 0:
        return abs(value - ref) / abs(ref)
    return abs(value - ref)


def closed_form_reference(q, expr, variables, run_value):
    """The closed form of q for one run: a number, or a history at the run's times."""
    if q.kind == "summary":
        return evaluate(expr, variables, "Reference/" + q.name)
    times = run_value[0]
    return (times, [evaluate(expr, dict(variables, t=t), "Reference/" + q.name) for t in times])


def fit_order(xs, es):
    """Least-squares slope of log e against log x (None with < 2 points)."""
    pts = [(math.log(x), math.log(e)) for x, e in zip(xs, es) if x > 0 and e and e > 0 and math.isfinite(e)]
    if len(pts) < 2:
        return None
    mx = sum(p[0] for p in pts) / len(pts)
    my = sum(p[1] for p in pts) / len(pts)
    sxx = sum((p[0] - mx) ** 2 for p in pts)
    return sum((p[0] - mx) * (p[1] - my) for p in pts) / sxx if sxx > 0 else None


def pareto(points):
    """Indices of the points (cost, error) no other point beats in both."""
    out = []
    for i, (c, e) in enumerate(points):
        # Errors equal to 1e-6 (the same answer reached two ways, to a solver tolerance) count as equal.
        if not any((c2 <= c and e2 <= e * (1 + 1e-6)) and (c2 < c or e2 < e * (1 - 1e-6))
                   for j, (c2, e2) in enumerate(points) if j != i):
            out.append(i)
    return sorted(out, key=lambda i: points[i][0])


def median(xs):
    s = sorted(xs)
    n = len(s)
    return 0.0 if n == 0 else (s[n // 2] if n % 2 else 0.5 * (s[n // 2 - 1] + s[n // 2]))

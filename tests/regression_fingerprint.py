"""Fingerprints of anvil runs and their comparison (used by tests/regression.py).

A fingerprint is every number a run produces that is a *result*: the counts
and figures of summary.json and the columns of its CSV histories, each value
tagged with a group (a physical quantity within one file: forces,
displacements, stresses, energies, ...). Comparison is relative RTOL per
value, with an absolute floor per value so that round-off does not fail:

    |got - ref| <= max(RTOL |ref|, floor),
    floor = max(RTOL * scale(group), TINY[group], quantity-specific floor)

where scale(group) is the largest |value| of the group over the whole run in
the reference. The quantity-specific floors (see Floors below) are the
converged Newton residual of the row's step for forces and residuals (a
reaction on a free or contact face is the residual), and the round-off of the
heat content for the heat terms. So a free boundary's reaction (~1e-12 N
beside 1e3 N on the loaded one), a converged Newton residual, a balance error
(a difference of works, ~1e-14 beside them) compare only as "small"; Newton
rows on the round-off plateau compare by order of magnitude. Counts (steps,
cut-backs, iterations, ARKode statistics, active contact nodes, rows) must
match exactly.
"""
import csv
import json
import math
import os
import re

RTOL = 1e-10

# Absolute floor per group, used when the whole group is ~zero (its scale
# gives no floor): a little above what double round-off produces in it. A
# penetration is a gap, a difference of coordinates: its round-off is eps
# times the size of the bodies (1e-13 mm: bodies up to ~500 mm).
TINY = {"force": 1e-12, "displacement": 1e-15, "stress": 1e-12, "strain": 1e-15,
        "temperature": 1e-12, "energy": 1e-15, "heat": 1e-15, "heat_content": 1e-12,
        "work": 1e-15, "time": 1e-20, "time_step": 1e-20, "residual": 1e-14, "increment": 1e-18,
        "line_search": 1e-15, "penetration": 1e-13, "rate": 1e-12, "staggered": 1e-15,
        "ratio": 1e-12}
TINY_DEFAULT = 1e-15

# Not results: what they measure is the machine, not the computation.
EXCLUDED_SUMMARY = {
    "wall_time": "wall clock: machine and load dependent",
    "wall_time_per_phase": "wall clock per phase: machine and load dependent",
    "step_loop_wall_time": "wall clock of the step loop: machine and load dependent",
    "step_loop_cpu_time": "CPU seconds of the step loop: machine dependent",
    "cpu_time_per_phase": "CPU seconds per phase: machine dependent",
    "assembly_cells_per_second_per_process": "a rate measured by the wall clock",
    "peak_memory_MB": "memory: allocator, MPI and library dependent",
    "memory_per_dof_bytes": "memory per dof: derived from peak_memory_MB",
    "scene": "a path: where the scene file lives",
    "contact.pattern_rebuilds": "a cost (matrix patterns built for the contact), not an answer",
    "steady_heat.last_residuals": "steady Newton's residual history: it ends in round-off",
    "steady_heat.last_increments": "steady Newton's increment history: it ends in round-off",
}
EXCLUDED_COLUMNS = {
    ("thermal.csv", "mechanics_wall_time"): "wall clock of the mechanics per step",
    ("thermal.csv", "thermal_wall_time"): "wall clock of the heat solve per step",
}

# Integer counts: exact match.
EXACT_SUMMARY = {"dimension", "processes", "cells", "dofs", "temperature_dofs", "steps",
                 "cut_backs", "newton_iterations", "linear_iterations",
                 "heat.arkode_internal_steps", "heat.arkode_nonlinear_iterations",
                 "heat.staggered_iterations", "steady_heat.solves", "steady_heat.newton_iterations",
                 "steady_heat.last_newton_iterations"}
EXACT_COLUMN = re.compile(
    r"^(step|iteration|converged|arkode_steps|arkode_attempts|error_test_failures|"
    r"nonlinear_iterations|newton_iterations|nonlinear_failures|linear_setups|linear_solves|linear_iterations|"
    r"mass_solves|rhs_evaluations|staggered_iterations|return_iterations|local_iterations|"
    r".*_active_nodes|.*_sliding_nodes)$")

# "file:column" -> group, first match wins (":" starts the column name).
COLUMN_GROUPS = [
    (r":time$", "time"),
    (r":(time_step|last_internal_step)$", "time_step"),
    (r"^reactions\.csv:.*_F[xyz]$", "force"),
    (r"^contact\.csv:.*(_F[xyz]|_normal|_tangential)$", "force"),
    (r"^contact\.csv:.*(_friction_work|_heat_exchanged|_friction_heat)$", "work"),
    (r"^contact\.csv:.*_max_penetration$", "penetration"),
    (r"_u[xyz]$", "displacement"),
    (r"(_stress_..|:s[xyz][xyz]|:von_mises|:pressure)$", "stress"),
    (r"(equivalent_plastic_strain|:e[xyz][xyz])$", "strain"),
    (r"temperature$", "temperature"),
    # The mechanical balance error is W_ext - W_int - dK: compared on the
    # scale of the works it is the difference of; so are the stress-work
    # balance and the F-bar work (true minus material stress work, ~1e-13 of
    # them: round-off on its own scale).
    (r"^energy\.csv:(external_work|internal_work|kinetic_energy|plastic_work|elastic_energy|"
     r"stress_work|balance_error|stress_balance_error)$", "energy"),
    # The audit's other work terms (contact, flow plastic, thermal, hypoelastic
    # volume, F-bar): works too, on the same scale; alone, a term that is zero
    # in a scene (F-bar work ~1e-14 N mm in two_blocks) has no scale of its own.
    (r"^energy\.csv:.*_work$", "energy"),
    # heat_content carries rho c T0 V (large); its changes and the heat terms,
    # the heat balance error among them, have their own, smaller scale.
    (r"^energy\.csv:heat_content$", "heat_content"),
    (r"^energy\.csv:heat_", "heat"),
    (r"^energy\.csv:.*_heat(_in)?$", "heat"),
    (r"^newton\.csv:residual$", "residual"),
    (r"^newton\.csv:increment$", "increment"),
    (r"^newton\.csv:line_search$", "line_search"),
    (r"^thermal\.csv:staggered_change$", "staggered"),
    (r"^thermal\.csv:staggered_contraction$", "ratio"),
    (r"_rate$", "rate"),
    # Steady heat: the last residual and increment are round-off, compared on
    # the scale of the first residual and of the temperatures.
    (r"^steady_heat\.csv:residual_(first|last)$", "residual"),
    (r"^steady_heat\.csv:increment_last$", "temperature"),
    (r"^steady_heat\.csv:.*_heat_in$", "heat"),
]


def column_group(filename, column):
    if EXACT_COLUMN.match(column):
        return "exact"
    key = "%s:%s" % (filename, column)
    for pattern, group in COLUMN_GROUPS:
        if re.search(pattern, key):
            return group
    return column  # its own group: floor from its own scale


def summary_group(key, qoi_groups):
    """Group of a flattened summary key ('energy.external_work', ...)."""
    if key in EXACT_SUMMARY:
        return "exact"
    section, _, name = key.partition(".")
    if section == "quantities_of_interest":
        return "qoi_" + qoi_groups.get(name, name)
    if section == "energy":
        return "energy"
    if section == "heat":
        if name == "heat_content":
            return "heat_content"
        return "ratio" if name == "arkode_steps_per_step" else "heat"
    if section == "contact":
        return column_group("contact.csv", name)
    if section == "steady_heat" and name.endswith("_heat_in"):
        return "steady_heat"
    return key  # time: its own group


# --- Quantities of interest: their group from their definition in the scene.

FIELD_GROUPS = [(r"^u[xyz]$", "displacement"), (r"^(stress_..|von_mises|pressure)$", "stress"),
                (r"temperature", "temperature"), (r"plastic_strain", "strain")]
CONTACT_GROUPS = {"normal": "force", "tangential": "force", "x": "force", "y": "force",
                  "z": "force", "friction_work": "work", "heat_exchanged": "work",
                  "friction_heat": "work", "max_penetration": "penetration"}


def qoi_definition(scene, sets):
    """The 'Output/Quantities of interest' entry of a scene, --set overrides applied."""
    for s in sets:
        path, _, value = s.partition("=")
        if path.strip() == "Output/Quantities of interest":
            return value
    text = open(scene).read().replace("\\\n", " ")
    stack, found = [], ""
    for line in text.splitlines():
        line = line.split("#")[0].strip()
        if line.startswith("subsection "):
            stack.append(line[len("subsection "):].strip())
        elif line == "end" and stack:
            stack.pop()
        elif stack == ["Output"] and re.match(r"set\s+Quantities of interest\s*=", line):
            found = line.split("=", 1)[1]
    return found


def qoi_groups(definition):
    """name -> group, from 'name: reaction(b, x); name2: probe(p, uy) ...'."""
    groups = {}
    for item in definition.split(";"):
        name, _, expr = item.partition(":")
        m = re.search(r"(\w+)\s*\(\s*([^,)]*)\s*(?:,\s*([^,)]*))?\)", expr)
        if not name.strip() or not m:
            continue
        func, a, b = m.group(1), m.group(2).strip(), (m.group(3) or "").strip()
        if func == "reaction":
            group = "force"
        elif func == "contact":
            group = CONTACT_GROUPS.get(b, b)
        else:
            field = b if func == "probe" else a
            group = next((g for p, g in FIELD_GROUPS if re.search(p, field)), field)
        groups[name.strip()] = group
    return groups


# --- Collecting a fingerprint.

def flatten(d, prefix=""):
    for k, v in d.items():
        key = prefix + k
        if isinstance(v, dict):
            yield from flatten(v, key + ".")
        else:
            yield key, v


def summary_fingerprint(summary, qoi_defs):
    """Numbers of summary.json (grouped) and its strings (compared exactly)."""
    values, strings = {}, {}
    for key, v in flatten(summary):
        if key.split(".")[0] in EXCLUDED_SUMMARY or key in EXCLUDED_SUMMARY:
            continue
        if isinstance(v, str):
            strings[key] = v
        elif isinstance(v, (int, float)) or v is None:
            values[key] = {"group": summary_group(key, qoi_defs), "value": v}
    return {"values": values, "strings": strings}


def csv_fingerprint(path):
    filename = os.path.basename(path)
    with open(path) as f:
        rows = list(csv.reader(f))
    header, body = rows[0], rows[1:]
    columns = {}
    for i, name in enumerate(header):
        # Columns are matched by name; a header's " [unit]" is not part of it
        # (so references recorded before units were added still compare).
        name = name.split(" [", 1)[0].strip()
        if (filename, name) in EXCLUDED_COLUMNS:
            continue
        columns[name] = {"group": column_group(filename, name),
                         "values": [float(r[i]) for r in body]}
    return {"rows": len(body), "columns": columns}


# --- Comparison.

# Forces are balanced only to the Newton residual of their step: on a free or
# contact face the reaction *is* the residual, so each force (and residual) has
# the converged residual of its step as an absolute floor. Rows of newton.csv
# within PLATEAU of their step's converged residual are on the round-off
# plateau (a penalty contact stalls there): residual and increment are
# compared by order of magnitude only, the line-search factor not at all.
FORCE_GROUPS = {"force", "qoi_force", "residual"}
PLATEAU = 100.0
# heat_content_change is content - content0 (content ~ rho c T V): its
# round-off, and that of the heat terms balanced against it, is ~eps x content.
HEAT_CONTENT_ROUNDOFF = 1e-13


def group_scales(columns):
    """Largest |value| of each group over the run (reference side)."""
    scales = {}
    for c in columns.values():
        finite = [abs(v) for v in c["values"] if v is not None and math.isfinite(v)]
        scales[c["group"]] = max([scales.get(c["group"], 0.0)] + finite)
    return scales


def within_magnitude(ref, got, floor):
    """Order of magnitude: within a factor 10, or both below the floor."""
    if abs(ref) <= floor and abs(got) <= floor:
        return True
    return ref != 0 and got != 0 and (ref > 0) == (got > 0) and abs(math.log10(got / ref)) <= 1


def differs(ref, got, group, floor, loose=False):
    """None if got matches ref, else the relative difference (inf for counts)."""
    if ref is None or got is None or not (math.isfinite(ref) and math.isfinite(got)):
        return None if repr(ref) == repr(got) else math.inf
    if group == "exact":
        return None if ref == got else math.inf
    floor = max(floor, TINY.get(group, TINY_DEFAULT))
    if loose:
        return None if within_magnitude(ref, got, floor) else abs(got - ref) / max(abs(ref), floor)
    diff = abs(got - ref)
    if diff <= max(RTOL * abs(ref), floor):
        return None
    return diff / abs(ref) if ref else math.inf


def newton_levels(files):
    """step -> the residual its Newton iteration converged to (its last row)."""
    newton = files.get("newton.csv", {}).get("columns", {})
    if "residual" not in newton:
        return {}
    return dict(zip(newton["step"]["values"], newton["residual"]["values"]))


def heat_floor(ref):
    """Absolute floor of the heat terms: round-off of the heat content."""
    contents = [abs(v["value"]) for k, v in ref["summary"]["values"].items()
                if k == "heat.heat_content" and v["value"] is not None]
    energy = ref["files"].get("energy.csv", {}).get("columns", {}).get("heat_content")
    contents += [abs(v) for v in energy["values"]] if energy else []
    return HEAT_CONTENT_ROUNDOFF * max(contents + [0.0])


class Floors:
    """The absolute floor of each value: its group's scale, and for forces
    the Newton level of its row's step, for heat the heat content's round-off."""

    def __init__(self, ref, columns, steps):
        self.scales = group_scales(columns)
        self.levels = newton_levels(ref["files"])
        self.last_level = self.levels[max(self.levels)] if self.levels else 0.0
        self.steps, self.heat = steps, heat_floor(ref)

    def __call__(self, group, row):
        floor = RTOL * self.scales[group]
        if group in FORCE_GROUPS:
            step = self.steps[row] if self.steps else None
            floor = max(floor, self.levels.get(step, 0.0) if step is not None else self.last_level)
        if group == "heat":
            floor = max(floor, self.heat)
        return floor


def plateau_rows(columns, levels):
    """Rows of newton.csv on the round-off plateau of their step."""
    if "residual" not in columns:
        return set()
    rows = zip(columns["step"]["values"], columns["residual"]["values"])
    return {i for i, (step, r) in enumerate(rows) if r <= PLATEAU * levels.get(step, 0.0)}


def compare_columns(case, where, ref, got, floors, out, loose_rows=()):
    """Append one line per differing value of ref/got {name: {group, values}}."""
    for name, r in ref.items():
        if name not in got:
            out.append("%s %s %s: column missing" % (case, where, name))
            continue
        for row, (a, b) in enumerate(zip(r["values"], got[name]["values"])):
            loose = row in loose_rows and r["group"] in ("residual", "increment", "line_search")
            if loose and r["group"] == "line_search":
                continue  # a step taken on round-off: its length is noise
            d = differs(a, b, r["group"], floors(r["group"], row), loose)
            if d is not None:
                out.append("%s %s %s row %d: reference %.17g got %.17g relative difference %.3g"
                           % (case, where, name, row, a, b, d))
    for name in got:
        if name not in ref:
            out.append("%s %s %s: column not in the reference" % (case, where, name))


def compare(case, ref, got):
    """All differences between two fingerprints, one line each."""
    out = []
    rs, gs = ref["summary"], got["summary"]
    for key, v in rs["strings"].items():
        if gs["strings"].get(key) != v:
            out.append("%s summary.json %s: reference %r got %r" % (case, key, v, gs["strings"].get(key)))
    as_columns = lambda s: {k: {"group": v["group"], "values": [v["value"]]} for k, v in s["values"].items()}
    summary = as_columns(rs)
    compare_columns(case, "summary.json", summary, as_columns(gs), Floors(ref, summary, None), out)
    for name, r in ref["files"].items():
        g = got["files"].get(name)
        if g is None:
            out.append("%s %s: file missing" % (case, name))
            continue
        if r["rows"] != g["rows"]:
            out.append("%s %s: %d rows, reference %d" % (case, name, g["rows"], r["rows"]))
        # Groups by today's rules, not those stored with the reference: a
        # rule refined later applies without re-recording every case.
        columns = {k: dict(c, group=column_group(name, k)) for k, c in r["columns"].items()}
        steps = columns["step"]["values"] if "step" in columns else None
        floors = Floors(ref, columns, steps)
        loose = plateau_rows(columns, floors.levels) if name == "newton.csv" else ()
        compare_columns(case, name, columns, g["columns"], floors, out, loose)
    for name in got["files"]:
        if name not in ref["files"]:
            out.append("%s %s: file not in the reference" % (case, name))
    return out


def load(path):
    with open(path) as f:
        return json.load(f)


def save(path, fingerprint):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w") as f:
        json.dump(fingerprint, f, indent=1, sort_keys=True)
        f.write("\n")

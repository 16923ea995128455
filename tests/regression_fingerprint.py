"""Fingerprints of anvil runs and their comparison (used by tests/regression.py).

A fingerprint is every number a run produces that is a *result*: the counts
and figures of summary.json and the columns of its CSV histories, each value
tagged with a group (a physical quantity within one file: forces,
displacements, stresses, energies, ...). Comparison is relative RTOL per
value, with an absolute floor per group so that round-off does not fail:

    |got - ref| <= max(RTOL |ref|, RTOL * scale(group), TINY[group])

where scale(group) is the largest |value| of the group over the whole run in
the reference. A free boundary's reaction (~1e-12 N beside 1e3 N on the loaded
one), a converged Newton residual (~1e-12 N beside the first residual of the
run), a balance error (a difference of works, ~1e-14 beside them) are all
round-off: the group floor compares them only as "small". Counts (steps,
cut-backs, iterations, active contact nodes) must match exactly.
"""
import csv
import json
import math
import os
import re

RTOL = 1e-10

# Absolute floor per group, used when the whole group is ~zero (its scale
# gives no floor): a little above what double round-off produces in it.
TINY = {"force": 1e-12, "displacement": 1e-15, "stress": 1e-12, "strain": 1e-15,
        "temperature": 1e-12, "energy": 1e-15, "heat": 1e-15, "heat_content": 1e-12,
        "work": 1e-15, "time": 1e-20, "residual": 1e-14, "increment": 1e-18,
        "line_search": 1e-15, "penetration": 1e-18, "rate": 1e-12, "staggered": 1e-15,
        "ratio": 1e-12}
TINY_DEFAULT = 1e-15

# Not results: what they measure is the machine, not the computation.
EXCLUDED_SUMMARY = {
    "wall_time": "wall clock: machine and load dependent",
    "wall_time_per_phase": "wall clock per phase: machine and load dependent",
    "assembly_cells_per_second_per_process": "a rate measured by the wall clock",
    "peak_memory_MB": "memory: allocator, MPI and library dependent",
    "memory_per_dof_bytes": "memory per dof: derived from peak_memory_MB",
    "scene": "a path: where the scene file lives",
}
EXCLUDED_COLUMNS = {
    ("thermal.csv", "mechanics_wall_time"): "wall clock of the mechanics per step",
    ("thermal.csv", "thermal_wall_time"): "wall clock of the heat solve per step",
}

# Integer counts: exact match.
EXACT_SUMMARY = {"dimension", "processes", "cells", "dofs", "temperature_dofs", "steps",
                 "cut_backs", "newton_iterations", "linear_iterations",
                 "heat.arkode_internal_steps", "heat.arkode_nonlinear_iterations",
                 "heat.staggered_iterations"}
EXACT_COLUMN = re.compile(
    r"^(step|iteration|converged|arkode_steps|arkode_attempts|error_test_failures|"
    r"nonlinear_iterations|nonlinear_failures|linear_setups|linear_solves|linear_iterations|"
    r"mass_solves|rhs_evaluations|staggered_iterations|return_iterations|local_iterations|"
    r".*_active_nodes|.*_sliding_nodes)$")

# Column name -> group, first match wins (the file name is matched too).
COLUMN_GROUPS = [
    (r"^(time|time_step|last_internal_step)$", "time"),
    (r"^reactions\.csv:.*_F[xyz]$", "force"),
    (r"^contact\.csv:.*(_F[xyz]|_normal|_tangential)$", "force"),
    (r"^contact\.csv:.*(_friction_work|_heat_exchanged|_friction_heat)$", "work"),
    (r"^contact\.csv:.*_max_penetration$", "penetration"),
    (r"_u[xyz]$", "displacement"),
    (r"(_stress_..|^s[xyz][xyz]|^von_mises|^pressure)$", "stress"),
    (r"(equivalent_plastic_strain|^e[xyz][xyz])$", "strain"),
    (r"temperature$", "temperature"),
    # The mechanical balance error is W_ext - W_int - dK: compared on the
    # scale of the works it is the difference of.
    (r"^energy\.csv:(external_work|internal_work|kinetic_energy|plastic_work|elastic_energy|"
     r"stress_work|balance_error)$", "energy"),
    # heat_content carries rho c T0 V (large); its changes and the heat terms
    # have their own, smaller scale.
    (r"^energy\.csv:heat_content$", "heat_content"),
    (r"^energy\.csv:heat_", "heat"),
    (r"^energy\.csv:.*_heat(_in)?$", "heat"),
    (r"^newton\.csv:residual$", "residual"),
    (r"^newton\.csv:increment$", "increment"),
    (r"^newton\.csv:line_search$", "line_search"),
    (r"^thermal\.csv:staggered_change$", "staggered"),
    (r"^thermal\.csv:staggered_contraction$", "ratio"),
    (r"_rate$", "rate"),
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
        if key.split(".")[0] in EXCLUDED_SUMMARY:
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
        if (filename, name) in EXCLUDED_COLUMNS:
            continue
        columns[name] = {"group": column_group(filename, name),
                         "values": [float(r[i]) for r in body]}
    return {"rows": len(body), "columns": columns}


# --- Comparison.

def group_scales(columns):
    """Largest |value| of each group over the run (reference side)."""
    scales = {}
    for c in columns.values():
        finite = [abs(v) for v in c["values"] if v is not None and math.isfinite(v)]
        scales[c["group"]] = max([scales.get(c["group"], 0.0)] + finite)
    return scales


def differs(ref, got, group, scale):
    """None if got matches ref, else the relative difference (inf for counts)."""
    if ref is None or got is None:
        return None if ref is got else math.inf
    if group == "exact":
        return None if ref == got else math.inf
    floor = max(RTOL * scale, TINY.get(group, TINY_DEFAULT))
    diff = abs(got - ref)
    if diff <= max(RTOL * abs(ref), floor):
        return None
    return diff / abs(ref) if ref else math.inf


def compare_columns(case, where, ref, got, out):
    """Append one line per differing value of ref/got {name: {group, values}}."""
    scales = group_scales(ref)
    for name, r in ref.items():
        if name not in got:
            out.append("%s %s %s: column missing" % (case, where, name))
            continue
        g = got[name]["values"]
        for row, (a, b) in enumerate(zip(r["values"], g)):
            d = differs(a, b, r["group"], scales[r["group"]])
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
    compare_columns(case, "summary.json", as_columns(rs), as_columns(gs), out)
    for name, r in ref["files"].items():
        g = got["files"].get(name)
        if g is None:
            out.append("%s %s: file missing" % (case, name))
            continue
        if r["rows"] != g["rows"]:
            out.append("%s %s: %d rows, reference %d" % (case, name, g["rows"], r["rows"]))
        compare_columns(case, name, r["columns"], g["columns"], out)
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

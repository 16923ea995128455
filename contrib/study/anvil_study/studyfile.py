"""Reading a study file (doc/study.md): deal.II ParameterHandler syntax,
`subsection NAME` / `set ENTRY = VALUE` / `end`, '#' comments, '\\' continued
lines. The tool parses it itself (a study is not a scene), so every error is
one line `FILE:LINE: what was wrong and what was expected`.

Inside `Set`, `Ladder NAME`, `Reference/Run`, `Stability/Entries` and the
variants of `Physics cost`, an entry whose name holds a '/' is a scene entry
('Time/Time step'), exactly what `anvil --set` takes.
"""
import os
import re

ROLES = ("time step", "mesh size", "scheme", "parameter")
MODES = ("ladder", "stability", "physics cost")


class StudyInputError(Exception):
    """Bad input: the message is one line naming file, line and parameter."""


class Node:
    def __init__(self, name, line):
        self.name, self.line = name, line
        self.entries = {}      # name -> (value, line), in file order
        self.children = {}     # name -> Node, in file order


def read_tree(path):
    """The file as a tree of Nodes; syntax errors raise StudyInputError."""
    try:
        with open(path) as f:
            raw = f.read().split("\n")
    except OSError as e:
        raise StudyInputError("%s: cannot read the study file (%s)" % (path, e.strerror))
    root, stack, pending, start = Node("", 0), [], "", 0
    for number, text in enumerate(raw, 1):
        text = text.split("#", 1)[0].rstrip()
        if text.endswith("\\"):
            pending, start = pending + text[:-1] + " ", start or number
            continue
        line, at = (pending + text).strip(), start or number
        pending, start = "", 0
        if not line:
            continue
        node = stack[-1] if stack else root
        words = line.split(None, 1)
        if words[0] == "subsection" and len(words) == 2:
            name = " ".join(words[1].split())
            if name in node.children:
                raise StudyInputError("%s:%d: subsection '%s' given twice" % (path, at, name))
            child = Node(name, at)
            node.children[name] = child
            stack.append(child)
        elif line == "end":
            if not stack:
                raise StudyInputError("%s:%d: 'end' without a subsection" % (path, at))
            stack.pop()
        elif words[0] == "set" and len(words) == 2 and "=" in words[1]:
            name, value = words[1].split("=", 1)
            name = " ".join(name.split())
            if name in node.entries:
                raise StudyInputError("%s:%d: entry '%s' given twice" % (path, at, name))
            node.entries[name] = (value.strip(), at)
        else:
            raise StudyInputError("%s:%d: expected 'subsection NAME', 'set ENTRY = VALUE' or 'end', not '%s'"
                                  % (path, at, line))
    if stack:
        raise StudyInputError("%s:%d: subsection '%s' is not closed by 'end'" % (path, stack[-1].line, stack[-1].name))
    return root


class Ladder:
    """One ladder: scene entries stepped together (paired); ladders are crossed."""

    def __init__(self, name, line, role, values, entries, optional=()):
        self.name, self.line, self.role, self.optional = name, line, role, list(optional)
        self.values = values          # numeric level per step (for orders and plots), or None
        self.entries = entries        # [(scene path, [value per level])]

    def __len__(self):
        return len(self.entries[0][1])

    def label(self, i):
        if self.values is not None:
            return "%.6g" % self.values[i]
        return self.entries[0][1][i]

    def drop(self, i):
        """Remove level i (an optional level this build does not have)."""
        if self.values is not None:
            self.values = self.values[:i] + self.values[i + 1:]
        self.entries = [(p, v[:i] + v[i + 1:]) for p, v in self.entries]

    def overrides(self, i):
        return [(path, values[i]) for path, values in self.entries]


class Quantity:
    """summary: a name of summary.json (a quantity of interest, or a dotted
    path like heat.balance_error); history: a CSV column compared in an
    L2-in-time norm."""

    def __init__(self, name, kind, key, file=None, line=0):
        self.name, self.kind, self.key, self.file, self.line = name, kind, key, file, line


class Study:
    pass


def _number(text, path, line, what, positive=False, integer=False):
    try:
        v = int(text) if integer else float(text)
    except ValueError:
        raise StudyInputError("%s:%d: %s: expected a%s number, not '%s'"
                              % (path, line, what, "n integer" if integer else "", text))
    if positive and v <= 0 or v < 0:
        raise StudyInputError("%s:%d: %s: expected a %s number, not '%s'"
                              % (path, line, what, "positive" if positive else "non-negative", text))
    return v


def _check_known(node, known, path, where):
    for name, (_, line) in node.entries.items():
        if name not in known:
            raise StudyInputError("%s:%d: unknown entry '%s' in %s (expected one of: %s)"
                                  % (path, line, name, where, ", ".join(known)))


def scene_entries(node, path, where):
    """The scene overrides of a subsection: every entry must be a scene path."""
    out = []
    for name, (value, line) in node.entries.items():
        if "/" not in name:
            raise StudyInputError("%s:%d: '%s' in %s is not a scene entry (expected 'Section/Entry', "
                                  "as for anvil --set)" % (path, line, name, where))
        out.append((name, value))
    return out


def _ladder(node, path):
    name = node.name[len("Ladder"):].strip()
    if not name:
        raise StudyInputError("%s:%d: a ladder needs a name: 'subsection Ladder NAME'" % (path, node.line))
    entries, role, values, optional = [], None, None, []
    for key, (value, line) in node.entries.items():
        if key == "Optional levels":
            optional = [v.strip() for v in value.split("|") if v.strip()]
        elif key == "Role":
            if value not in ROLES:
                raise StudyInputError("%s:%d: ladder '%s': Role '%s' (expected one of: %s)"
                                      % (path, line, name, value, ", ".join(ROLES)))
            role = value
        elif key == "Value":
            values = (value, line)
        elif "/" in key:
            levels = [v.strip() for v in value.split("|")] if value.strip() else []
            if not levels or any(v == "" for v in levels):
                raise StudyInputError("%s:%d: ladder '%s' is empty or has an empty level: '%s' "
                                      "(expected values separated by '|')" % (path, line, name, key))
            entries.append((key, levels, line))
        else:
            raise StudyInputError("%s:%d: ladder '%s': unknown entry '%s' (expected Role, Value, Optional "
                                  "levels or a scene entry 'Section/Entry')" % (path, line, name, key))
    if not entries:
        raise StudyInputError("%s:%d: ladder '%s' is empty (expected at least one scene entry "
                              "'set Section/Entry = v1 | v2 | ...')" % (path, node.line, name))
    n = len(entries[0][1])
    for key, levels, line in entries:
        if len(levels) != n:
            raise StudyInputError("%s:%d: ladder '%s': '%s' has %d levels, '%s' has %d (paired entries "
                                  "need the same number)" % (path, line, name, key, len(levels),
                                                             entries[0][0], n))
    if values is not None:
        texts = [v.strip() for v in values[0].split("|")]
        if len(texts) != n:
            raise StudyInputError("%s:%d: ladder '%s': Value has %d levels, the entries %d"
                                  % (path, values[1], name, len(texts), n))
        values = [_number(t, path, values[1], "ladder '%s' Value" % name) for t in texts]
    else:
        try:
            values = [float(v) for v in entries[0][1]]
        except ValueError:
            values = None
    if role is None:
        paths = [e[0] for e in entries]
        role = ("time step" if "Time/Time step" in paths else
                "scheme" if "Physics/Coupling" in paths else "parameter")
    if role in ("time step", "mesh size") and values is None:
        raise StudyInputError("%s:%d: ladder '%s' (role %s) needs numeric levels: set Value = v1 | v2 | ..."
                              % (path, node.line, name, role))
    for o in optional:
        if o not in entries[0][1]:
            raise StudyInputError("%s:%d: ladder '%s': optional level '%s' is not one of its levels (%s)"
                                  % (path, node.line, name, o, " | ".join(entries[0][1])))
    return Ladder(name, node.line, role, values, [(k, v) for k, v, _ in entries], optional)


def _quantities(node, path):
    out = []
    for name, (value, line) in node.entries.items():
        words = value.split(None, 1)
        if not words or words[0] not in ("summary", "history"):
            raise StudyInputError("%s:%d: quantity '%s': expected 'summary [NAME]' or 'history FILE.csv: "
                                  "COLUMN', not '%s'" % (path, line, name, value))
        if words[0] == "summary":
            out.append(Quantity(name, "summary", words[1].strip() if len(words) > 1 else name, line=line))
        else:
            m = re.match(r"^(\S+\.csv)\s*:\s*(.+)$", words[1].strip() if len(words) > 1 else "")
            if not m:
                raise StudyInputError("%s:%d: quantity '%s': expected 'history FILE.csv: COLUMN', not '%s'"
                                      % (path, line, name, value))
            out.append(Quantity(name, "history", m.group(2).strip(), m.group(1), line))
    return out


STUDY_KEYS = ("Scene", "Name", "Mode", "Output directory", "Repeats", "Concurrent runs", "MPI processes",
              "Threads per run", "Timeout", "Accuracy quantity", "Accuracy levels")


def read_study(path):
    """The Study of a file; every structural error raises StudyInputError."""
    root = read_tree(path)
    known = ("Study", "Set", "Quantities", "Reference", "Stability", "Physics cost")
    for name, child in root.children.items():
        if name not in known and not name.startswith("Ladder"):
            raise StudyInputError("%s:%d: unknown subsection '%s' (expected Study, Set, Ladder NAME, Quantities, "
                                  "Reference, Stability or Physics cost)" % (path, child.line, name))
    for name, (_, line) in root.entries.items():
        raise StudyInputError("%s:%d: entry '%s' outside a subsection (expected it in subsection Study)"
                              % (path, line, name))
    if "Study" not in root.children:
        raise StudyInputError("%s:1: no 'subsection Study' (expected at least 'set Scene = FILE.prm' in it)" % path)
    node = root.children["Study"]
    _check_known(node, STUDY_KEYS, path, "subsection Study")
    get = lambda k, d="": node.entries.get(k, (d, node.line))
    s = Study()
    s.path = path
    scene, line = get("Scene")
    if not scene:
        raise StudyInputError("%s:%d: Study/Scene: expected the scene file (.prm) the study runs" % (path, line))
    s.scene = scene if os.path.isabs(scene) else os.path.normpath(os.path.join(os.path.dirname(path), scene))
    if not os.path.isfile(s.scene):
        raise StudyInputError("%s:%d: Study/Scene: no such scene file '%s'" % (path, line, s.scene))
    s.name = get("Name", os.path.splitext(os.path.basename(path))[0])[0]
    s.mode, line = get("Mode", "ladder")
    if s.mode not in MODES:
        raise StudyInputError("%s:%d: Study/Mode: '%s' (expected one of: %s)" % (path, line, s.mode, ", ".join(MODES)))
    s.output = get("Output directory", os.path.join("output", "study", s.name))[0]
    num = lambda key, default, positive, integer: _number(get(key, default)[0], path, get(key)[1],
                                                          "Study/" + key, positive, integer)
    s.repeats = num("Repeats", "1", True, True)
    s.jobs = num("Concurrent runs", "0", False, True)
    s.np = num("MPI processes", "1", True, True)
    s.threads = num("Threads per run", "0", False, True)
    s.timeout = num("Timeout", "0", False, False)
    s.accuracy_quantity, s.accuracy_line = get("Accuracy quantity")
    levels, line = get("Accuracy levels", "1e-2, 1e-3, 1e-4, 1e-5, 1e-6")
    s.accuracy_levels = [_number(t.strip(), path, line, "Study/Accuracy levels", True) for t in levels.split(",")]

    s.sets = scene_entries(root.children["Set"], path, "subsection Set") if "Set" in root.children else []
    s.ladders = [_ladder(c, path) for n, c in root.children.items() if n.startswith("Ladder")]
    names = [l.name for l in s.ladders]
    for l in s.ladders:
        if names.count(l.name) > 1:
            raise StudyInputError("%s:%d: two ladders named '%s'" % (path, l.line, l.name))
    s.quantities = _quantities(root.children["Quantities"], path) if "Quantities" in root.children else []
    _reference(s, root.children.get("Reference"), path)
    s.stability = root.children.get("Stability")
    s.variants = []
    if "Physics cost" in root.children:
        pc = root.children["Physics cost"]
        for name, (_, line) in pc.entries.items():
            raise StudyInputError("%s:%d: Physics cost: '%s' (expected one subsection per variant with the "
                                  "scene entries it changes)" % (path, line, name))
        for name, child in pc.children.items():
            entries = scene_entries(child, path, "Physics cost/%s" % name)
            if not entries:
                raise StudyInputError("%s:%d: Physics cost variant '%s' changes nothing (expected scene entries)"
                                      % (path, child.line, name))
            s.variants.append((name, entries))
    _check_mode(s, root, path)
    return s


def _reference(s, node, path):
    s.reference_type, s.reference_values, s.reference_run = "none", {}, []
    if node is None:
        return
    for name, child in node.children.items():
        if name != "Run":
            raise StudyInputError("%s:%d: Reference: unknown subsection '%s' (expected Run)" % (path, child.line, name))
    rtype, line = node.entries.get("Type", ("closed form", node.line))
    if rtype not in ("closed form", "finest", "run"):
        raise StudyInputError("%s:%d: Reference/Type: '%s' (expected closed form, finest or run)" % (path, line, rtype))
    s.reference_type = rtype
    qnames = [q.name for q in s.quantities]
    for name, (value, vline) in node.entries.items():
        if name in ("Type", "Error"):
            continue
        if name not in qnames:
            raise StudyInputError("%s:%d: Reference: quantity '%s' does not exist (the study's quantities: %s)"
                                  % (path, vline, name, ", ".join(qnames) or "none"))
        s.reference_values[name] = (value, vline)
    s.error_kind, line = node.entries.get("Error", ("relative", node.line))
    if s.error_kind not in ("relative", "absolute"):
        raise StudyInputError("%s:%d: Reference/Error: '%s' (expected relative or absolute)" % (path, line, s.error_kind))
    if rtype == "closed form":
        for q in s.quantities:
            if q.name not in s.reference_values:
                raise StudyInputError("%s:%d: Reference: no closed form for quantity '%s' (expected 'set %s = "
                                      "EXPRESSION')" % (path, node.line, q.name, q.name))
    if rtype == "run":
        if "Run" not in node.children:
            raise StudyInputError("%s:%d: Reference/Type = run needs 'subsection Run' with the scene entries of "
                                  "the reference run" % (path, line))
        s.reference_run = scene_entries(node.children["Run"], path, "Reference/Run")
    if rtype == "finest" and not any(l.role in ("time step", "mesh size") for l in s.ladders):
        raise StudyInputError("%s:%d: Reference/Type = finest needs a ladder with Role time step or mesh size"
                              % (path, line))


def _check_mode(s, root, path):
    if s.mode == "ladder":
        if not s.ladders:
            raise StudyInputError("%s:1: a ladder study needs at least one 'subsection Ladder NAME'" % path)
        if not s.quantities:
            raise StudyInputError("%s:1: a ladder study needs 'subsection Quantities' with at least one quantity"
                                  % path)
        if "Reference" not in root.children:
            raise StudyInputError("%s:1: a ladder study needs 'subsection Reference' (closed form, finest or run)"
                                  % path)
    if s.accuracy_quantity and s.accuracy_quantity not in [q.name for q in s.quantities]:
        raise StudyInputError("%s:%d: Study/Accuracy quantity: '%s' is not one of the quantities (%s)"
                              % (path, s.accuracy_line, s.accuracy_quantity,
                                 ", ".join(q.name for q in s.quantities)))
    if s.mode == "stability" and s.stability is None:
        raise StudyInputError("%s:1: Mode = stability needs 'subsection Stability'" % path)
    if s.mode == "physics cost" and not s.variants:
        raise StudyInputError("%s:1: Mode = physics cost needs 'subsection Physics cost' with one subsection "
                              "per variant" % path)

"""Every part registered in the sources is what the program offers, and
nothing else: for each registry, the names in the registration macros of
source/ (read from the files, independently of the program) equal the
selection the program accepts for the parameter that chooses it, read from
the one-line refusal of a name that does not exist; and each name appears in
that parameter's --help text.
"""
import glob
import os
import re
import subprocess

from anvil_test import ANVIL, SOURCE_DIR, check, finish

# Registry kind -> (scene, parameter choosing it).
KINDS = {
    "COUPLING_SCHEME": ("prm/necking_bar.prm", "Physics/Coupling"),
    "MATERIAL_MODEL": ("tests/plastic_block.prm", "Bodies/body/Material/Model"),
    "HARDENING_LAW": ("tests/plastic_block.prm", "Bodies/body/Material/Hardening/Model"),
    "THERMAL_SOFTENING": ("tests/plastic_block.prm", "Bodies/body/Material/Hardening/Thermal softening/Model"),
    "TOOL_SHAPE": ("tests/contact_block.prm", "Contact/floor/Type"),
}
macro = re.compile(r'ANVIL_REGISTER_([A-Z_]+)\(\s*(?:[23]\s*,\s*)?[\w:<>]+\s*,\s*"([^"]+)"', re.S)
registered = {k: set() for k in KINDS}
for f in glob.glob(os.path.join(SOURCE_DIR, "source", "**", "*.cc"), recursive=True):
    for kind, name in macro.findall(open(f, encoding="utf-8").read()):
        if kind in registered:
            registered[kind].add(name)

help_text = " ".join(w for w in subprocess.run([ANVIL, "--help"], capture_output=True, text=True).stdout.split() if w != "#")
for kind, (scene, parameter) in KINDS.items():
    p = subprocess.run([ANVIL, os.path.join(SOURCE_DIR, scene), "--check", "--set",
                        parameter + "=no such part"], capture_output=True, text=True)
    m = re.search(r"\[Selection ([^\]]*?) ?\]", p.stderr)
    offered = set(m.group(1).split("|")) if m else set()
    check(p.returncode == 2 and offered == registered[kind],
          "%s: the sources register %s; %s offers %s" % (kind, sorted(registered[kind]), parameter, sorted(offered)))
    if kind != "TOOL_SHAPE":  # tools are documented per named tool, not in the scene-less --help
        missing = [n for n in registered[kind] if "'%s':" % n not in help_text]
        check(not missing, "%s: every registered name is documented in --help (missing: %s)" % (kind, missing))
finish()

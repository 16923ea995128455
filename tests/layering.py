"""The shape of the code (doc/architecture.md), checked so it stays:

1. Layering: a file under include/anvil/X or source/X includes anvil headers
   only from the folders X may depend on (no include cycles between concerns;
   material does not include mechanics, contact does not include thermal).
2. Mirroring: every folder of include/anvil has a source/ folder of the same
   name with its implementation.
3. Size: no source or header file over 600 lines unless it says why in a
   comment containing 'long because'.
4. One instantiation macro: no instantiation for dim 2 or 3 spelled out by
   hand in source/ ('template class X<2>;', 'template void X<3>::f();'):
   ANVIL_INSTANTIATE / ANVIL_INSTANTIATE_CLASS instead.
"""
import os
import re
import sys

from anvil_test import SOURCE_DIR, check, finish

# What each concern may include (besides itself). Independent of the code: this
# table is the design (doc/architecture.md).
ALLOWED = {
    "core": set(),
    "geometry": {"core"},
    "material": {"core"},
    "thermal": {"core", "geometry"},
    "contact": {"core", "geometry"},
    "mechanics": {"core", "geometry", "material", "contact"},
    "coupling": {"core", "geometry", "material", "contact", "thermal", "mechanics"},
    "postprocess": {"core", "geometry", "material", "contact", "thermal", "mechanics", "coupling"},
    "simulator": {"core", "geometry", "material", "contact", "thermal", "mechanics", "coupling",
                  "postprocess"},
    "app": {"simulator"},
}
include_re = re.compile(r'#include\s*<anvil/([a-z_]+)/')

violations, long_files, hand_instantiations = [], [], []
for top in ("include/anvil", "source"):
    root = os.path.join(SOURCE_DIR, top)
    for folder in sorted(os.listdir(root)):
        path = os.path.join(root, folder)
        if not os.path.isdir(path):
            continue
        for dirpath, _, files in os.walk(path):
            for name in files:
                f = os.path.join(dirpath, name)
                text = open(f, encoding="utf-8").read()
                rel = os.path.relpath(f, SOURCE_DIR)
                if folder not in ALLOWED:
                    violations.append("%s: folder '%s' is not in the layer table" % (rel, folder))
                    continue
                for dep in include_re.findall(text):
                    if dep != folder and dep not in ALLOWED[folder]:
                        violations.append("%s includes anvil/%s/ (a %s file may include: %s)"
                                          % (rel, dep, folder, ", ".join(sorted(ALLOWED[folder])) or "core only"))
                n = text.count("\n")
                if n > 600 and "long because" not in text.lower():
                    long_files.append("%s: %d lines" % (rel, n))
                if top == "source" and re.search(r"^\s*template\s+[^\n(]*<[23]>", text, re.M):
                    hand_instantiations.append(rel)

for v in violations:
    print("  " + v)
check(not violations, "layering: every anvil include points down the layer table (%d violations)" % len(violations))

headers = {d for d in os.listdir(os.path.join(SOURCE_DIR, "include/anvil"))}
sources = {d for d in os.listdir(os.path.join(SOURCE_DIR, "source")) if d != "app"}
check(headers <= sources and sources <= headers,
      "include/anvil and source mirror each other (only in include: %s; only in source: %s)"
      % (sorted(headers - sources), sorted(sources - headers)))

for f in long_files:
    print("  " + f)
check(not long_files, "no file over 600 lines without a note saying why (%d)" % len(long_files))
for f in hand_instantiations:
    print("  hand-written instantiation: " + f)
check(not hand_instantiations, "one instantiation macro: %d files instantiate for dim 2 or 3 by hand"
      % len(hand_instantiations))
finish()

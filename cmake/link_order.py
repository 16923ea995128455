#!/usr/bin/env python3
"""Rank the shared libraries a run binds symbols to (cmake/link_order.txt).

The dynamic loader resolves each of anvil's ~330 000 start-up relocations
(deal.II 9.4's Debian package pulls in ~200 libraries: OpenCASCADE, gmsh,
VTK, PETSc) by walking the global scope, the executable's and then each
library's DT_NEEDED breadth first, until one library defines the symbol.
OpenCASCADE's and gmsh's own C++ symbols sit ~30-150 libraries deep, so the
walk took ~12.4 M steps on two_blocks. Libraries named early in libanvil's
DT_NEEDED enter the scope early: sorted by how many lookups they answer,
the walk is shorter. Binding results stay the same as long as no symbol is
defined by two libraries whose order changes: compare `LD_DEBUG=bindings`
before and after (this script's --compare).

    LD_DEBUG=bindings LD_DEBUG_OUTPUT=/tmp/b build/anvil prm/two_blocks.prm --check
    python3 cmake/link_order.py rank /tmp/b.PID > cmake/link_order.txt
    python3 cmake/link_order.py compare /tmp/before.PID /tmp/after.PID
"""
import collections
import os
import re
import subprocess
import sys

BINDING = re.compile(r"binding file (\S+) \[\d+\] to (\S+) \[\d+\]: \w+ symbol `([^']+)'")


def bindings(path):
    for line in open(path, errors="replace"):
        m = BINDING.search(line)
        if m:
            yield m.group(1), m.group(2), m.group(3)


def rank(path):
    """Sonames by the number of lookups they answer, most first (system libraries only)."""
    count = collections.Counter(os.path.basename(to) for _, to, _ in bindings(path))
    print("# Libraries in the order libanvil names them (DT_NEEDED), most symbol lookups first;")
    print("# written by cmake/link_order.py rank (two_blocks, Debian bookworm's deal.II 9.4.1).")
    for soname, n in count.most_common():
        if soname.startswith(("lib", "ld-")) and "anvil" not in soname and "vdso" not in soname:
            print("%s  # %d" % (soname, n))


def compare(before, after):
    """Every (referencing library, symbol) must bind to the same library in both
    runs, unless both definitions are vague linkage (WEAK or UNIQUE: inline
    functions, template instances, their static locals), of which the loader
    picks the first in scope for every reference alike."""
    def table(path):
        return {(os.path.basename(frm), sym): to for frm, to, sym in bindings(path)}
    kinds = {}

    def kind(library, symbol):
        if library not in kinds:
            out = subprocess.run(["readelf", "-W", "--dyn-syms", library], capture_output=True,
                                 text=True).stdout
            kinds[library] = {p[7].split("@")[0]: p[4] for p in map(str.split, out.splitlines())
                              if len(p) >= 8 and p[6] != "UND"}
        return kinds[library].get(symbol, "?")
    a, b = table(before), table(after)
    common = set(a) & set(b)
    moved = [k for k in common if a[k] != b[k]]
    strong = sorted(k for k in moved if {kind(a[k], k[1]), kind(b[k], k[1])} - {"WEAK", "UNIQUE"})
    for k in strong[:50]:
        print("%s: %s -> %s (was %s)" % (k[0], k[1], b[k], a[k]))
    print("%d bindings in both runs, %d bound to another copy of a vague-linkage symbol, "
          "%d to another definition; only before: %d, only after: %d"
          % (len(common), len(moved) - len(strong), len(strong), len(set(a) - set(b)),
             len(set(b) - set(a))))
    return 1 if strong else 0


if __name__ == "__main__":
    if len(sys.argv) == 3 and sys.argv[1] == "rank":
        rank(sys.argv[2])
    elif len(sys.argv) == 4 and sys.argv[1] == "compare":
        sys.exit(compare(sys.argv[2], sys.argv[3]))
    else:
        sys.exit(__doc__)

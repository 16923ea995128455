"""The raw appended VTU writer (Output/VTU encoding = raw, vtu_writer.cc)
against deal.II's zlib writer, its independent reference.

1. The same scene written both ways (2D dynamic with heat: the tube; 2D on two
   processes: the cantilever; 3D: the twisted bar): VTK (Debian's
   /usr/bin/python3) reads from both .pvtu the same points, cells, cell types
   and every point array bit for bit (both hold Float32).
   The contact point cloud (contact_*.vtu, Float64 raw against the ascii
   file's 10 digits): the same points and arrays to 1e-9 relative.
2. Our own reading of a raw file, without VTK: each DataArray's offset points
   at a UInt32 byte count followed by that many bytes, the blocks follow one
   another to the end of the appended section, and the displacement block
   holds what VTK read.
3. np 2 = np 1 (the arrays are written one at a time since session 23): the
   3D bar written raw on two processes holds, cell by cell (a cell found by
   its points), the arrays of the one-process file but rank, to the solver's
   tolerance (1e-6 of each array's largest value).
"""
import os
import re
import struct
import subprocess

from anvil_test import run, check, finish

READ_CONTACT = r"""
import json, sys, vtk
from vtk.util.numpy_support import vtk_to_numpy
out = []
for f in sys.argv[1:]:
    r = vtk.vtkXMLUnstructuredGridReader(); r.SetFileName(f); r.Update(); g = r.GetOutput()
    pd = g.GetPointData()
    d = {pd.GetArrayName(i): vtk_to_numpy(pd.GetArray(i)).ravel().tolist() for i in range(pd.GetNumberOfArrays())}
    d["points"] = vtk_to_numpy(g.GetPoints().GetData()).ravel().tolist()
    out.append(d)
print(json.dumps(out))
"""

READ = r"""
import json, sys, vtk
from vtk.util.numpy_support import vtk_to_numpy
def read(f):
    r = vtk.vtkXMLPUnstructuredGridReader(); r.SetFileName(f); r.Update(); return r.GetOutput()
out = {}
for f in sys.argv[1:]:
    g = read(f)
    pd = g.GetPointData()
    arrays = {pd.GetArrayName(i): vtk_to_numpy(pd.GetArray(i)).ravel().tolist()
              for i in range(pd.GetNumberOfArrays())}
    out[f] = {"points": vtk_to_numpy(g.GetPoints().GetData()).ravel().tolist(),
              "cells": vtk_to_numpy(g.GetCells().GetConnectivityArray()).tolist(),
              "types": [g.GetCellType(i) for i in range(g.GetNumberOfCells())],
              "arrays": arrays}
print(json.dumps(out))
"""


def last_pvtu(out):
    pvd = open(os.path.join(out, "solution.pvd")).read()
    return os.path.join(out, pvd.rsplit('file="', 1)[1].split('"')[0])


def vtk_read(*files):
    import json
    p = subprocess.run(["/usr/bin/python3", "-c", READ] + list(files), capture_output=True, text=True)
    if p.returncode != 0:
        print(p.stderr)
    return json.loads(p.stdout)


read = {}
CASES = [("prm/tube_impact.prm", ["Time/End time=1e-4"], 1),
         ("prm/cantilever.prm", ["Time/End time=0.2"], 2),
         ("prm/twisted_bar_3d.prm", ["Output/Field interval=0"], 1)]
for scene, sets, np in CASES:
    name = os.path.splitext(os.path.basename(scene))[0]
    files = {}
    for encoding in ("raw", "zlib"):
        out, _, _ = run(scene, sets + ["Output/VTU encoding=" + encoding], np=np,
                        name="vtu_%s_%s" % (name, encoding))
        files[encoding] = last_pvtu(out)
    data = vtk_read(files["raw"], files["zlib"])
    read[name] = data[files["raw"]]
    raw, zlib = data[files["raw"]], data[files["zlib"]]
    same = [k for k in zlib["arrays"] if raw["arrays"].get(k) == zlib["arrays"][k]]
    print("  %s (np %d): %d points, %d cells; %d of %d arrays equal bit for bit"
          % (name, np, len(zlib["points"]) // 3, len(zlib["types"]), len(same), len(zlib["arrays"])))
    check(len(zlib["types"]) > 0 and raw["points"] == zlib["points"], name + ": the same points")
    check(raw["cells"] == zlib["cells"] and raw["types"] == zlib["types"], name + ": the same cells")
    check(sorted(raw["arrays"]) == sorted(zlib["arrays"]) and len(same) == len(zlib["arrays"]),
          name + ": every point array the same")

    # 2. The raw file's layout, read by hand.
    piece = files["raw"].replace(".pvtu", ".0.vtu")
    blob = open(piece, "rb").read()
    start = blob.index(b'<AppendedData encoding="raw">')
    underscore = blob.index(b"_", start) + 1
    end = blob.rindex(b"</AppendedData>")
    header = blob[:start].decode()
    offsets = [int(o) for o in re.findall(r'offset="(\d+)"', header)]
    position = 0
    for o in offsets:
        if o != position:
            break
        (n,) = struct.unpack("<I", blob[underscore + position:underscore + position + 4])
        position += 4 + n
    tail = blob[underscore + position:end].strip()
    check(len(offsets) == len(zlib["arrays"]) + 4 and tail == b"",
          name + ": %d blocks, each at its offset, byte counts ending at the section's end"
          % len(offsets))
    m = re.search(r'Name="displacement" NumberOfComponents="3" format="appended" offset="(\d+)"', header)
    o = int(m.group(1))
    (n,) = struct.unpack("<I", blob[underscore + o:underscore + o + 4])
    values = list(struct.unpack("<%df" % (n // 4), blob[underscore + o + 4:underscore + o + 4 + n]))
    if np == 1:
        check(values == raw["arrays"]["displacement"], name + ": our reading of the displacement = VTK's")

    if any(f.startswith("contact_") for f in os.listdir(os.path.dirname(files["raw"]))):
        import json
        last = sorted(f for f in os.listdir(os.path.dirname(files["raw"])) if f.startswith("contact_"))[-1]
        pair = [os.path.join(os.path.dirname(files[e]), last) for e in ("raw", "zlib")]
        p = subprocess.run(["/usr/bin/python3", "-c", READ_CONTACT] + pair, capture_output=True, text=True)
        a, b = json.loads(p.stdout)
        worst = max(abs(x - y) / max(max(abs(v) for v in b[k]), 1e-300)
                    for k in b for x, y in zip(a[k], b[k])) if sorted(a) == sorted(b) else 1
        print("  %s contact: %d nodes, %d arrays, largest difference raw - ascii %.1e relative"
              % (name, len(b["points"]) // 3, len(b) - 1, worst))
        check(len(a["points"]) == len(b["points"]) > 0 and worst < 1e-9,
              name + ": contact fields raw = ascii to its 10 digits")

def by_cell(grid):
    """Each cell's points (the key) and each array's values at them."""
    n = len(grid["cells"]) // len(grid["types"])
    cells = {}
    for c in range(len(grid["types"])):
        ids = grid["cells"][n * c:n * c + n]
        key = tuple(tuple(grid["points"][3 * i:3 * i + 3]) for i in ids)
        values = {}
        for name, v in grid["arrays"].items():
            width = len(v) // (len(grid["points"]) // 3)
            values[name] = [v[width * i + k] for i in ids for k in range(width)]
        cells[key] = values
    return cells


# 3. The 3D bar on two processes against its one-process file.
out, _, _ = run("prm/twisted_bar_3d.prm", ["Output/Field interval=0", "Output/VTU encoding=raw"], np=2,
                name="vtu_twisted_bar_3d_raw_np2")
two = by_cell(vtk_read(last_pvtu(out))[last_pvtu(out)])
one = by_cell(read["twisted_bar_3d"])
names = sorted(n for n in next(iter(one.values())) if n != "rank")
worst = 0.0
for name in names:
    scale = max(max(abs(x) for x in cell[name]) for cell in one.values()) or 1.0
    for key, cell in one.items():
        if key in two:
            worst = max(worst, max(abs(x - y) for x, y in zip(cell[name], two[key][name])) / scale)
print("  twisted_bar_3d np 2: %d cells (np 1: %d), %d arrays, largest difference %.1e of the "
      "array's largest value" % (len(two), len(one), len(names), worst))
check(sorted(two) == sorted(one) and sorted(n for n in next(iter(two.values())) if n != "rank") == names,
      "twisted_bar_3d: np 2 writes the cells and arrays of np 1")
check(worst <= 1e-6, "twisted_bar_3d: np 2's arrays = np 1's to 1e-6 of each array's scale")
finish()

"""Nodal (recovered) stress and plastic strain in the VTU beside the cell values.

<field>_nodal is the volume-weighted mean of the cell values around each
vertex (patch averaging). Checks, reading the .pvtu with VTK (Debian's
/usr/bin/python3):
1. A homogeneous state (a square pulled uniformly): every nodal value equals
   the cell value (a mean of equal numbers).
2. In the uniform mesh of a bent cantilever, a vertex shared by four cells
   gets the plain mean of their four cell values (the VTU holds each cell's
   value at each of its corners; recomputed here).
3. np = 1 and np = 2 write the same nodal values at the same points
   (the sums across the processes' cells arrive through compress(add)).
"""
import json
import os
import subprocess

from anvil_test import run, check, finish

READ = r"""
import json, sys, vtk
from vtk.util.numpy_support import vtk_to_numpy
r = vtk.vtkXMLPUnstructuredGridReader(); r.SetFileName(sys.argv[1]); r.Update()
g = r.GetOutput()
pts = vtk_to_numpy(g.GetPoints().GetData())
out = {}
for name in sys.argv[2:]:
    v = vtk_to_numpy(g.GetPointData().GetArray(name))
    out[name] = {}
    for p, x in zip(pts, v):  # every patch's value at that point (one per cell)
        out[name].setdefault("%.6f,%.6f" % (p[0], p[1]), []).append(float(x))
print(json.dumps(out))
"""


def last_fields(out, names):
    pvd = open(os.path.join(out, "solution.pvd")).read()
    last = pvd.rsplit('file="', 1)[1].split('"')[0]
    p = subprocess.run(["/usr/bin/python3", "-c", READ, os.path.join(out, last)] + names,
                       capture_output=True, text=True)
    if p.returncode != 0:
        print(p.stderr)
    return json.loads(p.stdout)


# 1. Homogeneous uniaxial stretch of the unit square.
bc = "Boundary conditions/Displacement=left: ux = 0; bottom: uy = 0; right: ux = 0.01*t"
out, _, _ = run("tests/homogeneous.prm", [bc], name="nodal_homogeneous")
f = last_fields(out, ["von_mises", "von_mises_nodal", "stress_xx_nodal", "stress_xx"])
scale = max(max(v) for v in f["von_mises"].values())
diff = max(abs(n - c) for k in f["von_mises"] for n in f["von_mises_nodal"][k] for c in f["von_mises"][k])
print("  homogeneous: von Mises %.4f MPa, largest nodal - cell %.1e" % (scale, diff))
check(scale > 1 and diff < 1e-10 * scale, "homogeneous: nodal = cell values")
diff = max(abs(n - c) for k in f["stress_xx"] for n in f["stress_xx_nodal"][k] for c in f["stress_xx"][k])
check(diff < 1e-10 * scale, "homogeneous: stress_xx_nodal = stress_xx")

# 2-3. The cantilever (a stress gradient), np = 1 and 2.
sets = ["Time/End time=0.2", "Output/Field interval=0"]
o1, _, _ = run("prm/cantilever.prm", sets, name="nodal_np1")
o2, _, _ = run("prm/cantilever.prm", sets, np=2, name="nodal_np2")
a = last_fields(o1, ["von_mises_nodal", "von_mises"])
b = last_fields(o2, ["von_mises_nodal"])
inner = [k for k, v in a["von_mises"].items() if len(v) == 4]
diff = max(abs(a["von_mises_nodal"][k][0] - sum(a["von_mises"][k]) / 4) for k in inner)
scale = max(max(v) for v in a["von_mises_nodal"].values())
print("  cantilever: %d inner vertices, largest |nodal - mean of 4 cells| %.1e of %.1f MPa"
      % (len(inner), diff, scale))
# The VTU holds 32-bit floats: agreement to their round-off (~1e-7 relative).
check(len(inner) > 50 and diff < 1e-6 * scale, "inner vertex: nodal = mean of its four cells")
common = [k for k in a["von_mises_nodal"] if k in b["von_mises_nodal"]]
diff = max(abs(x - y) for k in common for x in a["von_mises_nodal"][k] for y in b["von_mises_nodal"][k])
print("  np = 1 vs 2: %d points, largest difference %.1e MPa" % (len(common), diff))
check(len(common) > 100 and diff < 1e-8 * scale, "np = 1 and np = 2 give the same nodal values")
finish()

#!/usr/bin/python3
"""anvil-render: a PNG of one field of an anvil run on its deformed mesh.

    anvil-render RUN --field temperature -o T.png                 # last output time
    anvil-render RUN --field von_mises_nodal --time 2e-3 -o vm.png  # nearest output time
    anvil-render RUN --list                                       # fields and times

RUN is an output directory (its solution.pvd). The mesh is drawn in its
deformed configuration (the displacement added to the points, true scale;
--undeformed for the reference one, --scale to magnify), coloured by the
field (a point or cell array; a vector or tensor by its magnitude, or
--component k), with a colour bar labelled with the field's unit and the
time in the title; a 3D mesh is drawn by its outer faces. VTK reads the
files and matplotlib draws them (no display needed).

Runs with Debian's /usr/bin/python3 (python3-vtk9, python3-matplotlib).
"""
import argparse
import os
import sys
import xml.etree.ElementTree as ElementTree

# Units of the fields anvil writes (mm, N, s, K; stresses in MPa).
UNITS = {"displacement": "mm", "velocity": "mm/s", "temperature": "K", "von_mises": "MPa",
         "pressure": "MPa", "J": "-", "equivalent_plastic_strain": "-", "body": "-", "rank": "-"}


def fail(message):
    sys.stderr.write("anvil-render: error: %s\n" % message)
    sys.exit(2)


def unit_of(field):
    name = field[:-len("_nodal")] if field.endswith("_nodal") else field
    if name.startswith("stress_"):
        return "MPa"
    return UNITS.get(name, "")


def records(run):
    """(time, file) of every field output of the run, from solution.pvd."""
    pvd = os.path.join(run, "solution.pvd")
    if not os.path.exists(pvd):
        fail("%s not found (is '%s' an anvil output directory with Field interval > 0?)"
             % (pvd, run))
    root = ElementTree.parse(pvd).getroot()
    out = [(float(d.get("timestep")), os.path.join(run, d.get("file")))
           for d in root.iter("DataSet")]
    if not out:
        fail("%s lists no data sets" % pvd)
    return sorted(out)


def read(path):
    import vtk
    reader = vtk.vtkXMLPUnstructuredGridReader() if path.endswith(".pvtu") else \
        vtk.vtkXMLUnstructuredGridReader()
    reader.SetFileName(path)
    reader.Update()
    return reader.GetOutput()


def array_names(grid):
    point = grid.GetPointData()
    cell = grid.GetCellData()
    return ([point.GetArrayName(i) for i in range(point.GetNumberOfArrays())],
            [cell.GetArrayName(i) for i in range(cell.GetNumberOfArrays())])


def geometry(grid, field, deformed, scale, component):
    """Points (deformed or not), cells (point-index lists) and the field's
    values per point or per cell (a vector or tensor by its magnitude)."""
    import numpy as np
    from vtk.util.numpy_support import vtk_to_numpy
    points = vtk_to_numpy(grid.GetPoints().GetData()).astype(float)
    pdata, cdata = grid.GetPointData(), grid.GetCellData()
    if deformed and pdata.GetArray("displacement") is not None:
        u = vtk_to_numpy(pdata.GetArray("displacement")).astype(float)
        points[:, :u.shape[1]] += scale * u
    on_points = pdata.GetArray(field) is not None
    values = vtk_to_numpy((pdata if on_points else cdata).GetArray(field)).astype(float)
    if values.ndim > 1:
        if component >= values.shape[1]:
            fail("field '%s' has %d components, not component %d" % (field, values.shape[1], component))
        values = values[:, component] if component >= 0 else np.linalg.norm(values, axis=1)
    cells = [[grid.GetCell(c).GetPointId(k) for k in range(grid.GetCell(c).GetNumberOfPoints())]
             for c in range(grid.GetNumberOfCells())]
    return points, cells, values, on_points


def surface(grid):
    """The outer faces of a 3D mesh (what is seen), as an unstructured grid."""
    import vtk
    f = vtk.vtkDataSetSurfaceFilter()
    f.SetInputData(grid)
    f.Update()
    return f.GetOutput()


def render(run, field, output, time=None, deformed=True, scale=1.0, component=-1):
    """Draws the field with matplotlib (VTK only reads: Debian's VTK cannot
    render without an X server); returns the time drawn."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np
    recs = records(run)
    t, path = recs[-1] if time is None else min(recs, key=lambda r: abs(r[0] - time))
    grid = read(path)
    points, cells_fields = array_names(grid)
    if field not in points and field not in cells_fields:
        fail("field '%s' not in %s (fields: %s)" % (field, path, ", ".join(points + cells_fields)))
    bounds = grid.GetBounds()
    flat = abs(bounds[5] - bounds[4]) <= 1e-12 * max(bounds[1] - bounds[0], bounds[3] - bounds[2])
    if not flat:
        grid = surface(grid)
    xyz, cells, values, on_points = geometry(grid, field, deformed, scale, component)
    lo, hi = float(np.nanmin(values)), float(np.nanmax(values))
    if hi <= lo:  # a uniform field still gets a readable colour bar
        lo, hi = lo - 0.5 * max(abs(lo), 1e-12), hi + 0.5 * max(abs(hi), 1e-12)
    norm = matplotlib.colors.Normalize(lo, hi)
    cmap = plt.get_cmap("viridis")
    edges = len(cells) < 5000  # element edges help on coarse meshes only
    if flat:
        fig, ax = plt.subplots(figsize=(8, 6))
        if on_points:
            # Two triangles per quad, Gouraud-shaded: the point values as written
            # (a cell field written by DataOut is constant per cell: still blocky).
            tri = [[c[0], c[1], c[2]] for c in cells] + [[c[0], c[2], c[3]] for c in cells if len(c) == 4]
            mappable = ax.tripcolor(xyz[:, 0], xyz[:, 1], tri, values, shading="gouraud",
                                    cmap=cmap, norm=norm)
        else:
            from matplotlib.collections import PolyCollection
            mappable = PolyCollection([xyz[c, :2] for c in cells], array=values, cmap=cmap, norm=norm)
            ax.add_collection(mappable)
        if edges:
            from matplotlib.collections import PolyCollection
            ax.add_collection(PolyCollection([xyz[c, :2] for c in cells], facecolors="none",
                                             edgecolors=(0.2, 0.2, 0.2, 0.5), linewidths=0.3))
        ax.set_aspect("equal")
        ax.autoscale_view()
        ax.set_xlabel("x [mm]")
        ax.set_ylabel("y [mm]")
    else:
        from mpl_toolkits.mplot3d.art3d import Poly3DCollection
        fig = plt.figure(figsize=(8, 6))
        ax = fig.add_subplot(projection="3d")
        face = np.array([values[c].mean() if on_points else values[i] for i, c in enumerate(cells)])
        coll = Poly3DCollection([xyz[c] for c in cells], facecolors=cmap(norm(face)),
                                edgecolors=(0.2, 0.2, 0.2, 0.4) if edges else "none",
                                linewidths=0.2)
        ax.add_collection3d(coll)
        for k, setter in enumerate((ax.set_xlim, ax.set_ylim, ax.set_zlim)):
            setter(xyz[:, k].min(), xyz[:, k].max())
        ax.set_box_aspect(np.ptp(xyz, axis=0) + 1e-12)
        ax.set_xlabel("x [mm]")
        ax.set_ylabel("y [mm]")
        ax.set_zlabel("z [mm]")
        mappable = matplotlib.cm.ScalarMappable(norm=norm, cmap=cmap)
    unit = unit_of(field)
    label = field + ("" if component < 0 else "[%d]" % component)
    fig.colorbar(mappable, ax=ax, orientation="horizontal", fraction=0.06, pad=0.12,
                 label="%s [%s]" % (label, unit) if unit else label)
    ax.set_title("%s: %s at t = %.4g s%s" % (os.path.basename(os.path.normpath(run)), label, t,
                                             "" if deformed else " (undeformed)"))
    fig.tight_layout()
    os.makedirs(os.path.dirname(os.path.abspath(output)), exist_ok=True)
    fig.savefig(output, dpi=120)
    plt.close(fig)
    return t


def main():
    p = argparse.ArgumentParser(prog="anvil-render", description=__doc__.split("\n\n")[0],
                                formatter_class=argparse.RawDescriptionHelpFormatter,
                                epilog=__doc__.split("\n\n", 1)[1])
    p.add_argument("run", help="an anvil output directory")
    p.add_argument("--field", help="the field to colour by")
    p.add_argument("--time", type=float, help="output time, s (the nearest is taken; default last)")
    p.add_argument("-o", "--output", help="PNG file")
    p.add_argument("--undeformed", action="store_true", help="draw the reference configuration")
    p.add_argument("--scale", type=float, default=1.0, help="displacement magnification")
    p.add_argument("--component", type=int, default=-1, help="component of a vector field")
    p.add_argument("--list", action="store_true", help="print the output times and fields")
    a = p.parse_args()
    if a.list:
        recs = records(a.run)
        points, cells = array_names(read(recs[-1][1]))
        print("times [s]: " + ", ".join("%.6g" % t for t, _ in recs))
        print("point fields: " + ", ".join(points))
        print("cell fields: " + ", ".join(cells))
        return
    if not a.field or not a.output:
        fail("expected --field NAME and -o FILE.png (or --list)")
    if not a.output.lower().endswith(".png"):
        fail("output '%s': expected a .png file" % a.output)
    t = render(a.run, a.field, a.output, a.time, not a.undeformed, a.scale, a.component)
    print("%s (t = %.6g s)" % (a.output, t))


if __name__ == "__main__":
    main()

"""Pictures: anvil-plot, anvil-render and a scene's standard figures.

1. A scene run with Output/Figures = true writes each item of its Figure list
   to <output>/figures/<name>.png: the files exist, are PNG images and are
   not blank (several colours, read back with matplotlib).
2. anvil-plot overlays two runs (PDF and PNG), labels the axes with the
   columns' units (read back from the PDF's text) and refuses an unknown
   column with exit 2 naming the columns it has.
3. anvil-render draws a field at a chosen time (the nearest output time).
4. A malformed Figure list is bad input: exit 2 before any work.
Needs Debian's /usr/bin/python3 with matplotlib, numpy and VTK
(contrib/setup.sh installs them).
"""
import os
import subprocess

from anvil_test import ANVIL, run, check, finish

TOOLS = os.path.dirname(os.path.abspath(ANVIL))
PLOT, RENDER = os.path.join(TOOLS, "anvil-plot"), os.path.join(TOOLS, "anvil-render")


def picture_ok(path):
    """(exists, is PNG, not blank): the pixel values of the image vary."""
    if not os.path.exists(path):
        return False, "missing"
    with open(path, "rb") as f:
        if f.read(8) != b"\x89PNG\r\n\x1a\n":
            return False, "not a PNG"
    p = subprocess.run(["/usr/bin/python3", "-c",
                        "import sys, matplotlib.image as m, numpy as n; a = m.imread(sys.argv[1]); "
                        "print(len(n.unique((a[..., :3] * 255).astype(int).reshape(-1, 3), axis=0)))",
                        path], capture_output=True, text=True)
    colours = int(p.stdout.strip() or 0)
    return colours > 20, "%d bytes, %d colours" % (os.path.getsize(path), colours)


def tool(args, status=0):
    p = subprocess.run(["/usr/bin/python3"] + args, capture_output=True, text=True)
    if p.returncode != status:
        print(p.stdout, p.stderr)
    check(p.returncode == status, "%s exits %d" % (" ".join(os.path.basename(a) for a in args[:2]), status))
    return p


# 1. The cantilever's standard figures (a history and a field).
fig = "Output/Figure list=tip: time -> tip_ux, tip_uy; von_mises: field von_mises"
a, s, _ = run("prm/cantilever.prm", ["Output/Figures=true", fig], name="figures_a")
for name in ("tip", "von_mises"):
    ok, what = picture_ok(os.path.join(a, "figures", name + ".png"))
    check(ok, "figures/%s.png written and not blank (%s)" % (name, what))

# 2. Two runs overlaid: the second with a stiffer material deflects less.
b, _, _ = run("prm/cantilever.prm", ["Output/Figures=false",
                                     "Bodies/beam/Material/Elasticity/Young's modulus=105000"],
              name="figures_b")
check(not os.path.exists(os.path.join(b, "figures")), "Output/Figures = false draws nothing")
pdf = os.path.join(a, "overlay.pdf")
tool([PLOT, a, b, "-x", "time", "-y", "tip_uy [mm]", "-o", pdf, "--label", "E = 70 GPa",
      "--label", "E = 105 GPa"])
data = open(pdf, "rb").read() if os.path.exists(pdf) else b""
check(data.startswith(b"%PDF") and len(data) > 5000, "overlay.pdf written (%d bytes)" % len(data))
png = os.path.join(a, "overlay.png")
tool([PLOT, a, b, "-x", "left_Fy", "-y", "tip_uy", "-o", png])
ok, what = picture_ok(png)
check(ok, "overlay.png (force against displacement) not blank (%s)" % what)
p = tool([PLOT, a, "-y", "no_such_column", "-o", png], status=2)
check("no column 'no_such_column'" in p.stderr and "tip_uy" in p.stderr,
      "unknown column named, with the columns there are")
p = tool([PLOT, a, "--list"])
check("tip_uy [mm]" in p.stdout and "left_Fy [N]" in p.stdout, "--list shows the columns with units")

# 3. A field at a chosen time.
t_png = os.path.join(a, "render.png")
p = tool([RENDER, a, "--field", "displacement", "--time", "0.33", "-o", t_png])
ok, what = picture_ok(t_png)
check(ok, "anvil-render displacement (%s): %s" % (p.stdout.strip(), what))

# 4. A malformed list stops before any work.
run("prm/cantilever.prm", ["Output/Figures=true", "Output/Figure list=tip time tip_ux"],
    name="figures_bad", expect_status=2)
print("PASS  malformed Figure list: exit 2")
finish()

"""Misspelled entries and subsections: "did you mean" with the nearest declared
names, and --help documenting a contact pair's and a tool's entries.

Each misspelling is made from a shipped scene by one edit; the message must
name the file and line (or --set), the subsection, and suggest the declared
name the misspelling came from; the exit status is 2 (bad input).
"""
import os
import subprocess

from anvil_test import ANVIL, SOURCE_DIR, WORK_DIR, check, finish

scene = open(os.path.join(SOURCE_DIR, "prm", "two_blocks.prm")).read()
work = os.path.join(WORK_DIR, "output", "suggestions")
os.makedirs(work, exist_ok=True)


def anvil(args):
    p = subprocess.run([ANVIL] + args, capture_output=True, text=True,
                       env=dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1",
                                OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1"))
    return p.returncode, p.stderr.strip(), p.stdout


def misspelled(old, new, expected, name):
    path = os.path.join(work, name + ".prm")
    assert old in scene, old
    text = scene.replace(old, new, 1)
    open(path, "w").write(text)
    line = text[:text.index(new)].count("\n") + 1
    status, err, _ = anvil([path, "--check"])
    print("  " + err)
    check(status == 2 and err.startswith("anvil: error: %s:%d: " % (path, line)) and expected in err,
          "%s: exit 2 at %s:%d with %s" % (name, os.path.basename(path), line, expected))


misspelled("set Time step = 5e-5", "set Time stpe = 5e-5", "did you mean 'Time step'?", "entry")
misspelled("set Conductivity = 150", "set conductivity = 150", "did you mean 'Conductivity'?", "case")
misspelled("subsection Time\n", "subsection Tmie\n", "did you mean 'Time'?", "subsection")
misspelled("set Friction coefficient = 0.2", "set Friction coeficient = 0.2",
           "in subsection 'Contact/interface' (did you mean 'Friction coefficient'?)", "pair_entry")

status, err, _ = anvil([os.path.join(SOURCE_DIR, "prm", "two_blocks.prm"), "--check",
                        "--set", "Time/End tme=1"])
print("  " + err)
check(status == 2 and "--set 'Time/End tme=1'" in err and "did you mean 'End time'?" in err,
      "--set with a misspelled entry suggests 'End time'")
status, err, _ = anvil([os.path.join(SOURCE_DIR, "prm", "two_blocks.prm"), "--check",
                        "--set", "Time/Qwxyz=1"])
print("  " + err)
check(status == 2 and "did you mean" not in err and "declared here: " in err and "'End time'" in err,
      "nothing near: no guess, the entries of the subsection are listed")
status, err, _ = anvil([os.path.join(SOURCE_DIR, "prm", "cantilever.prm"), "--check",
                        "--set", "Bodies/body/Material/Model=J2"])
print("  " + err)
check(status == 2 and "no subsection 'body' in subsection 'Bodies'" in err and "'beam'" in err,
      "--set through a body that does not exist names the bodies there are")
status, err, _ = anvil([os.path.join(SOURCE_DIR, "prm", "two_blocks.prm"), "--check",
                        "--set", "Time/Time step=abc"])
check(status == 2 and "did you mean" not in err, "a bad value of a declared entry is not a misspelling")

# Thermal only needs no elastic constants (prm/heat_half_space.prm gives none); with the
# mechanics the missing modulus is bad input, named.
status, err, _ = anvil([os.path.join(SOURCE_DIR, "prm", "heat_half_space.prm"), "--check"])
check(status == 0, "a thermal-only scene without elastic constants is valid")
status, err, _ = anvil([os.path.join(SOURCE_DIR, "prm", "heat_half_space.prm"), "--check",
                        "--set", "Physics/Coupling=isothermal split"])
print("  " + err)
check(status == 2 and "'Bodies/strip/Material/Elasticity/Young's modulus' and 'Bulk modulus' are "
      "both 0" in err, "with the mechanics, the missing modulus is named")
status, err, _ = anvil([os.path.join(SOURCE_DIR, "prm", "necking_bar.prm"), "--check",
                        "--set", "Geometry/Body name=bar"])
print("  " + err)
check(status == 2 and "Geometry/Body name" in err, "an unlisted mesh body points to the entry naming it")

status, _, help_text = anvil(["--help"])
pair = help_text[help_text.find("subsection <pair>"):]
tool = help_text[help_text.find("subsection <tool>"):]
check(status == 0 and "subsection <pair>" in help_text and "Slave" in pair and "Friction coefficient" in pair,
      "--help documents a contact pair's entries (Contact/<pair>)")
check("subsection <tool>" in help_text and "Motion" in tool and "Type" in tool,
      "--help documents a rigid tool's entries (Contact/<tool>)")
finish()

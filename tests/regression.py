"""Regression layer: every shipped scene and the scenes of the scene-level tests,
run with fixed settings, fingerprinted (tests/regression_fingerprint.py) and
compared with a reference recorded from the code at the commit that wrote it
(tests/regression/<case>.json).

Unlike the verification tests, which check against independent answers, this
only asks "did anything move?": a refactor that is meant to change no result
must pass it unchanged. A change that is meant to move results re-records the
references of the cases it moves, and says why in the commit message:

    tests/regression.py                  compare every case
    tests/regression.py CASE ...         compare these cases
    tests/regression.py --update CASE    re-record CASE (all cases without a name)
    tests/regression.py --list           the case table
    tests/regression.py --list-names     case names and process counts (for CMake)
    tests/regression.py --self-test      prove the comparison can fail

Environment as for the other scene tests (tests/anvil_test.py): ANVIL_EXECUTABLE,
ANVIL_SOURCE_DIR, ANVIL_TEST_WORK_DIR (scratch output under output/regression_<case>).
"""
import glob
import json
import os
import shutil
import sys
import time

import anvil_test
import regression_fingerprint as fp

REFERENCE_DIR = os.path.join(os.path.dirname(os.path.abspath(__file__)), "regression")

# Fields (VTU) are not fingerprinted: writing them only costs time.
QUIET = ["Output/Field interval=0", "Output/Verbosity=quiet"]


def scene(path, sets=(), np=1, note="as shipped"):
    return {"kind": "scene", "input": path, "sets": list(sets), "np": np, "note": note}


def point(path, sets=(), note="as shipped"):
    return {"kind": "point", "input": path, "sets": list(sets), "np": 1, "note": note}


CASES = {
    # Shipped scenes (prm/).
    "cantilever": scene("prm/cantilever.prm"),
    "twisted_bar_3d": scene("prm/twisted_bar_3d.prm"),
    "bimaterial_gmsh": scene("prm/bimaterial_gmsh.prm"),
    "thick_cylinder": scene("prm/thick_cylinder.prm"),
    "punch": scene("prm/punch.prm"),
    "necking_bar": scene("prm/necking_bar.prm"),
    "two_blocks": scene("prm/two_blocks.prm"),
    "heat_half_space": scene("prm/heat_half_space.prm"),
    "steady_slab": scene("prm/steady_slab.prm"),
    "necking_bar_thermal": scene("prm/necking_bar_thermal.prm", note="as shipped: adiabatic split"),
    # The other coupling schemes on the thermal necking bar, full length.
    "necking_bar_thermal_isothermal": scene(
        "prm/necking_bar_thermal.prm", ["Physics/Coupling=isothermal split"], note="isothermal split"),
    "necking_bar_thermal_staggered": scene(
        "prm/necking_bar_thermal.prm", ["Physics/Coupling=iterated staggered"], note="iterated staggered"),
    "necking_bar_thermal_monolithic": scene(
        "prm/necking_bar_thermal.prm", ["Physics/Coupling=monolithic", "Time/Time step=0.25"],
        note="monolithic, 20 steps of 0.25 s"),
    # Without a temperature field the temperature quantities do not exist.
    "necking_bar_thermal_mechanical": scene(
        "prm/necking_bar_thermal.prm", ["Physics/Coupling=mechanical only",
                                        "Output/Quantities of interest=neck_radius_change: probe(neck, ux); "
                                        "end_radius_change: probe(end, ux); final_force: reaction(top, y); "
                                        "neck_plastic_strain: probe(neck, equivalent_plastic_strain)"],
        note="mechanical only (the quantities of interest without temperatures)"),
    # Two processes, against its own np = 2 reference.
    "two_blocks_np2": scene("prm/two_blocks.prm", ["Time/End time=1e-3"], np=2,
                            note="np = 2, shortened to t = 1 ms: pressing and the first 0.9 of the 3.75 mm slide (full: ~40 s on a loaded machine)"),
    "tube_impact": scene("prm/tube_impact.prm", ["Time/End time=1.5e-4"],
                         note="case 3 shortened to the first peak (0.15 ms, 12 steps; the full crush is ~40 s)"),
    "quarter_cylinder_forming": scene("prm/quarter_cylinder_forming.prm", ["Time/End time=10"],
                                      note="shortened to the first 10 s of the ramp (the sheet swings onto the die and wraps its first half; full run ~7 s CPU)"),
    "taylor_bar": scene("prm/taylor_bar.prm", ["Time/End time=1.2e-5"],
                        note="shortened to the first 12 us (30 steps) of the 80 us impact"),
    # Material-point driver files.
    "mp_j2_cyclic": point("prm/material_point/j2_cyclic.prm"),
    "mp_johnson_cook": point("prm/material_point/johnson_cook.prm"),
    "mp_simple_shear": point("prm/material_point/simple_shear.prm"),
    "mp_stretch_rotate": point("prm/material_point/stretch_rotate.prm"),
    "mp_uniaxial_stress": point("prm/material_point/uniaxial_stress.prm"),
    # Scenes of the scene-level tests, as those tests run them.
    "contact_block": scene("tests/contact_block.prm",
                           note="as contact_friction.py's first run (stick then slip on a rigid plane)"),
    "contact_conduction": scene("tests/contact_conduction.prm",
                                note="as shipped: non-matching meshes (two_blocks.py part 3)"),
    "contact_patch": scene("tests/contact_patch.prm",
                           note="as shipped: one-pass, non-matching 5/7, c_N = 1e8 (contact_patch.py)"),
    "dynamics_bar": scene("tests/dynamics_bar.prm",
                          ["Mechanics/Dynamics/Initial velocity=ux = 1*sin(pi*x/200)",
                           "Mechanics/Dynamics/Spectral radius=0.5", "Time/End time=1.6e-5"],
                          note="dynamics_energy.py: smooth mode, rho_inf = 0.5, 10 steps"),
    "homogeneous_patch": scene("tests/homogeneous.prm", [
        "Boundary conditions/Displacement=" + "; ".join(
            "%s: ux = 0.5*t*x, uy = -0.2*t*y" % b for b in ("left", "right", "bottom", "top"))],
        # Fragile by construction: the exact patch leaves residuals of ~1e-13 N,
        # so whether a step takes 0 or 1 Newton iteration is decided by whether
        # the extrapolated predictor misses t*x by one ulp on the boundary
        # (has_jump in MechanicalProblem::newton). Kept as patch_stretch.py runs it.
        note="patch_stretch.py: stretch 1.5 x 0.8 of the distorted mesh, 20 steps"),
    "homogeneous_heating": scene("tests/homogeneous.prm", [
        "Bodies/body/Material/Model=J2", "Bodies/body/Material/Hardening/Initial yield stress=300",
        "Bodies/body/Material/Hardening/Hardening modulus=1000",
        "Bodies/body/Material/Elasticity/Young's modulus=200000",
        "Bodies/body/Material/Elasticity/Taylor-Quinney coefficient=0.9",
        "Physics/Coupling=isothermal split", "Heat/Initial temperature=293",
        "Mechanics/Newton/Residual tolerance=1e-10", "Mechanics/Newton/Absolute residual tolerance=0",
        "Boundary conditions/Displacement=" + "; ".join(
            "%s: ux = 0.2*t*x, uy = (1/(1 + 0.2*t) - 1)*y" % b for b in ("left", "right", "bottom", "top")),
        "Output/Quantities of interest=p: max(equivalent_plastic_strain); "
        "p_min: min(equivalent_plastic_strain); J: mean(J)"],
        note="thermal_coupling.py: plastic heating, isothermal split"),
    "plastic_block_heat": scene("tests/plastic_block.prm", [
        "Physics/Coupling=adiabatic split", "Time/Time step=0.1",
        "Bodies/body/Material/Elasticity/Thermal expansion=1.2e-5",
        "Bodies/body/Material/Hardening/Thermal softening/Model=linear",
        "Bodies/body/Material/Hardening/Thermal softening/Softening coefficient=2e-3",
        "Bodies/body/Material/Hardening/Thermal softening/Reference temperature=293",
        "Heat/Boundary conditions/Convection=bottom: 0.5, 293", "Output/Probes=corner: 1.1, 1",
        "Output/Quantities of interest=T: mean(temperature); Tmax: max(temperature); "
        "Tc: probe(corner, temperature); F: reaction(bottom, y)"],
        note="checkpoint_restart.py's heat scene: adiabatic split, softening, convection"),
}


def run_case(name, case):
    """Run one case into a clean scratch directory; its fingerprint."""
    source = os.path.join(anvil_test.SOURCE_DIR, case["input"])
    tag = "regression_" + name
    if case["kind"] == "point":
        path, _, _ = anvil_test.run_point(source, case["sets"], name=tag)
        return {"summary": {"values": {}, "strings": {}},
                "files": {"point.csv": fp.csv_fingerprint(path)}}
    out = os.path.join(anvil_test.WORK_DIR, "output", tag)
    shutil.rmtree(out, ignore_errors=True)  # no stale file from an earlier run
    sets = QUIET + case["sets"]
    out, summary, _ = anvil_test.run(source, sets, np=case["np"], name=tag)
    groups = fp.qoi_groups(fp.qoi_definition(source, sets))
    files = {os.path.basename(p): fp.csv_fingerprint(p) for p in sorted(glob.glob(out + "/*.csv"))}
    return {"summary": fp.summary_fingerprint(summary, groups), "files": files}


def reference_path(name):
    return os.path.join(REFERENCE_DIR, name + ".json")


def with_settings(name, case, fingerprint):
    """The fingerprint as stored: with the settings that produced it."""
    stored = {"case": name, "input": case["input"], "sets": case["sets"], "np": case["np"]}
    stored.update(fingerprint)
    return stored


def check_case(name, update):
    """Run, then record or compare; the list of differences (empty: passed)."""
    case = CASES[name]
    start = time.time()
    got = run_case(name, case)
    seconds = time.time() - start
    if update:
        fp.save(reference_path(name), with_settings(name, case, got))
        print("recorded %-32s %6.1f s  %s" % (name, seconds, reference_path(name)))
        return []
    if not os.path.exists(reference_path(name)):
        return ["%s: no reference %s (record it with --update %s)" % (name, reference_path(name), name)]
    ref = fp.load(reference_path(name))
    if (ref["input"], ref["sets"], ref["np"]) != (case["input"], case["sets"], case["np"]):
        return ["%s: the case's settings changed since its reference was recorded "
                "(re-record with --update %s)" % (name, name)]
    diffs = fp.compare(name, ref, got)
    print("%-6s %-32s %6.1f s  %d values compared" % ("PASS" if not diffs else "FAIL", name, seconds,
                                                    count_values(ref)))
    return diffs


def count_values(fingerprint):
    n = len(fingerprint["summary"]["values"]) + len(fingerprint["summary"]["strings"])
    for f in fingerprint["files"].values():
        n += sum(len(c["values"]) for c in f["columns"].values())
    return n


def self_test():
    """The comparison passes on an unchanged fingerprint and fails on a 0.3 %
    change of one result, or one more Newton iteration, or when the scene is
    run with a 0.3 % stiffer material; values may move by round-off (below
    the floor of their group) without failing."""
    import copy
    failures, checks = [], []
    ref = fp.load(reference_path("cantilever"))

    def expect(what, got, should_fail):
        diffs = fp.compare("self-test", ref, got)
        ok = bool(diffs) == should_fail
        checks.append(what)
        print("%s  %s: %d difference(s)%s" % ("PASS" if ok else "FAIL", what, len(diffs),
                                              (" — " + diffs[0]) if diffs else ""))
        if not ok:
            failures.append(what)

    expect("unchanged fingerprint passes", copy.deepcopy(ref), False)
    got = copy.deepcopy(ref)
    got["summary"]["values"]["quantities_of_interest.tip_uy"]["value"] *= 1.003
    expect("tip_uy (a quantity of interest) x 1.003 fails", got, True)
    got = copy.deepcopy(ref)
    column = got["files"]["reactions.csv"]["columns"]["left_Fy"]["values"]
    column[len(column) // 2] *= 1.003
    expect("one reaction in mid-run x 1.003 fails", got, True)
    got = copy.deepcopy(ref)
    got["summary"]["values"]["newton_iterations"]["value"] += 1
    expect("one more Newton iteration fails", got, True)
    # Round-off of a reordered sum: 1e-12 of the run's largest reaction on the
    # (nearly free) right end, 1e-12 of the largest residual on the last one.
    got = copy.deepcopy(ref)
    reactions = got["files"]["reactions.csv"]["columns"]
    scale = max(abs(v) for c in reactions.values() if c["group"] == "force" for v in c["values"])
    reactions["right_Fx"]["values"][-1] += 1e-12 * scale
    residual = got["files"]["newton.csv"]["columns"]["residual"]["values"]
    residual[-1] += 1e-12 * max(residual)
    expect("round-off (1e-12 of the run's scale) on a small reaction and a residual passes", got, False)
    # End to end: the scene run with a stiffer beam (E x 1.003) must fail.
    stiffer = dict(CASES["cantilever"])
    stiffer["sets"] = stiffer["sets"] + ["Bodies/beam/Material/Elasticity/Young's modulus=70210"]
    expect("cantilever run with E x 1.003 fails", run_case("self_test_stiffer", stiffer), True)
    return len(checks), failures


def main(argv):
    update = "--update" in argv
    names = [a for a in argv if not a.startswith("--")]
    if "--list-names" in argv:  # for tests/CMakeLists.txt: one ctest per case
        for name, case in CASES.items():
            print(name, case["np"])
        return 0
    if "--list" in argv:
        for name, case in CASES.items():
            print("%-32s np=%d  %-40s %s" % (name, case["np"], case["input"], case["note"]))
        return 0
    if "--self-test" in argv:
        checks, failures = self_test()
        print("%d passed, %d failed" % (checks - len(failures), len(failures)))
        return 1 if failures else 0
    unknown = [n for n in names if n not in CASES]
    if unknown:
        print("unknown case(s): %s (see --list)" % ", ".join(unknown))
        return 2
    diffs = []
    for name in names or list(CASES):
        diffs += check_case(name, update)
    for line in diffs:
        print(line)
    if diffs:
        print("%d value(s) differ from the reference" % len(diffs))
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))

#!/usr/bin/env bash
# Every bad input is refused before any work: exit status 2 and one line on
# stderr naming the file (and line, where it is in the file), the parameter
# and what was expected.
set -u
anvil="$1"; src="$2"
cd "$(mktemp -d)"
fail=0
expect() { # description, regex the message must match, command...
  local what="$1" regex="$2"; shift 2
  local err; err=$("$@" 2>&1 >/dev/null); local status=$?
  local lines; lines=$(printf '%s\n' "$err" | grep -c .)
  if [ $status -eq 2 ] && [ "$lines" -eq 1 ] && printf '%s' "$err" | grep -Eq -- "$regex"; then
    echo "PASS  $what: $err"
  else
    echo "FAIL  $what (exit $status, $lines line(s)): $err"; fail=1
  fi
  [ -d output ] && { echo "FAIL  $what: output was written before the error"; fail=1; rm -rf output; }
}
b="$src/tests/bad"
expect "misspelled entry"   "misspelled_entry.prm:3: .*End tme"            "$anvil" "$b/misspelled_entry.prm"
expect "wrong type"         "wrong_type.prm:3: .*one second.*End time.*"    "$anvil" "$b/wrong_type.prm"
expect "unknown subsection" "unknown_section.prm:2: .*Mechanix"            "$anvil" "$b/unknown_section.prm"
expect "missing mesh file"  "missing_mesh.prm:4: 'Geometry/Mesh file'.*no_such_mesh.msh" "$anvil" "$b/missing_mesh.prm"
expect "unknown boundary"   "unknown_boundary.prm:3: .*'lft'.*left"        "$anvil" "$b/unknown_boundary.prm"
expect "unknown body"       "unknown_body.prm:6: 'Bodies/Names'.*beam"     "$anvil" "$b/unknown_body.prm"
expect "bad expression"     "bad_expression.prm:3: .*0.5\*tt"              "$anvil" "$b/bad_expression.prm"
expect "Poisson's ratio 0.5" "bad_poisson.prm:7: .*Poisson's ratio.*0.5"   "$anvil" "$b/bad_poisson.prm"
expect "body not in Names" "body_not_listed.prm:3: .*Bodies.bar.*Bodies/Names" "$anvil" "$b/body_not_listed.prm"
expect "inverted block"     "bad_block.prm:3: 'Geometry/Blocks'"           "$anvil" "$b/bad_block.prm"
expect "missing scene file" "nonexistent.prm: cannot open"                 "$anvil" nonexistent.prm
expect "bad --set entry"    "--set 'Time/End tme=2'"                       "$anvil" "$src/prm/cantilever.prm" --set "Time/End tme=2"
expect "bad --set value"    "--set 'Time/End time=soon'"                   "$anvil" "$src/prm/cantilever.prm" --set "Time/End time=soon"
expect "malformed --set"    "expected 'Section/Subsection/Entry=value'"     "$anvil" "$src/prm/cantilever.prm" --set "Time/End time"
expect "bad direct solver limit" "Direct solver limit.*expected a number of DoFs >= 0 or .measured." "$anvil" "$src/prm/cantilever.prm" --set "Mechanics/Linear solver/Direct solver limit=lots"
expect "bad heat direct solver limit" "Heat/Linear solver/Direct solver limit.*expected a number of DoFs >= 0 or .measured." "$anvil" "$src/prm/two_blocks.prm" --set "Heat/Linear solver/Direct solver limit=-5"
expect "bad direct solver" "--set 'Mechanics/Linear solver/Direct solver=lu'.*auto\|klu\|band" "$anvil" "$src/prm/cantilever.prm" --set "Mechanics/Linear solver/Direct solver=lu"
expect "bad AMG smoother degree" "AMG smoother degree.*expected 'automatic' or an integer in \[1, 10\]" "$anvil" "$src/prm/cantilever.prm" --set "Mechanics/Linear solver/AMG smoother degree=2.5"
expect "bad AMG Chebyshev ratio" "AMG Chebyshev ratio.*expected 'automatic' or a number" "$anvil" "$src/prm/cantilever.prm" --set "Mechanics/Linear solver/AMG Chebyshev ratio=wide"
expect "bad AMG isochoric modes" "--set 'Mechanics/Linear solver/AMG isochoric modes=sometimes'.*automatic\|true\|false" "$anvil" "$src/prm/cantilever.prm" --set "Mechanics/Linear solver/AMG isochoric modes=sometimes"
expect "bad AMG aggregation threshold" "--set 'Mechanics/Linear solver/AMG aggregation threshold=2'" "$anvil" "$src/prm/cantilever.prm" --set "Mechanics/Linear solver/AMG aggregation threshold=2"
expect "bad AMG coarse size" "--set 'Mechanics/Linear solver/AMG coarse size=0'" "$anvil" "$src/prm/cantilever.prm" --set "Mechanics/Linear solver/AMG coarse size=0"
expect "bad AMG cycle" "--set 'Mechanics/Linear solver/AMG cycle=F'.*automatic\|V\|W" "$anvil" "$src/prm/cantilever.prm" --set "Mechanics/Linear solver/AMG cycle=F"
expect "bad AMG prolongator" "--set 'Mechanics/Linear solver/AMG prolongator=smooth'" "$anvil" "$src/prm/cantilever.prm" --set "Mechanics/Linear solver/AMG prolongator=smooth"
expect "bad GMRES restart" "--set 'Mechanics/Linear solver/GMRES restart=0'" "$anvil" "$src/prm/cantilever.prm" --set "Mechanics/Linear solver/GMRES restart=0"
expect "unknown option"     "unknown option '--frobnicate'"               "$anvil" "$src/prm/cantilever.prm" --frobnicate
expect "bad probe"          "--set: 'Output/Probes'"                       "$anvil" "$src/prm/cantilever.prm" --set "Output/Probes=tip: 10"
expect "unknown QoI probe"  "'Output/Quantities of interest'.*no probe named 'tap'" "$anvil" "$src/prm/cantilever.prm" --set "Output/Quantities of interest=a: probe(tap, ux)"
expect "reaction in a thermal-only scene" "--set: 'Output/Quantities of interest'.*reaction.*needs the mechanics.*thermal only" "$anvil" "$src/prm/heat_half_space.prm" --set "Output/Quantities of interest=r: reaction(left, x)"
expect "maximum step below the first" "--set: 'Time/Maximum time step' = 0.01 s must not be smaller than Time step" "$anvil" "$src/prm/necking_bar.prm" --set "Time/Maximum time step=0.01"
expect "steady heat without an outlet" "steady_slab.prm:[0-9]+: 'Heat/Time integration/Method'.*steady.*no boundary has a Temperature, Convection or Radiation.*singular" "$anvil" "$src/prm/steady_slab.prm" --set "Heat/Boundary conditions/Temperature=" --set "Heat/Boundary conditions/Convection=" --set "Heat/Boundary conditions/Radiation=" --set "Heat/Boundary conditions/Flux=right: 1"
expect "steady method in a coupled scene" "steady_slab.prm:[0-9]+: 'Heat/Time integration/Method'.*steady.*'isothermal split'.*Initial temperature field = steady" "$anvil" "$src/prm/steady_slab.prm" --set "Physics/Coupling=isothermal split" --set "Bodies/slab/Material/Elasticity/Young's modulus=1e5"
expect "unwritable output directory" "'Output/Directory' = '/proc/anvil_cannot' cannot be created" "$anvil" "$src/prm/necking_bar.prm" --set "Output/Directory=/proc/anvil_cannot"
expect "unknown coupling"   "--set 'Physics/Coupling=heat'.*heat.*mechanical only.*thermal only" "$anvil" "$src/prm/heat_half_space.prm" --set "Physics/Coupling=heat"
expect "mechanics in a thermal-only scene" "--set: 'Boundary conditions/Displacement' is given, but Physics/Coupling is 'thermal only'" "$anvil" "$src/prm/heat_half_space.prm" --set "Boundary conditions/Displacement=left: ux = 0"
# Contact pairs and rigid tools (tests/contact_block.prm: pair 'sliding' of
# the boundary 'bottom' on the plane tool 'floor', mu = 0.3, c_T = 1e4).
c="$src/tests/contact_block.prm"
d3=(--set "Dimension=3" --set "Geometry/Blocks=block: 0, 0, 0, 1, 1, 1, 2, 2, 2" --set "Contact/floor/Point=0, 0, 0"
    --set "Contact/floor/Normal=0, 1, 0" --set "Contact/floor/Center=0, 0, 0" --set "Contact/floor/Motion=0, 0, 0"
    --set "Output/Probes=" --set "Output/Quantities of interest=" --set "Boundary conditions/Displacement=top: ux = 0")
expect "contact: unknown Slave boundary (file)" "contact_unknown_slave.prm:20: .*'nowhere'.*left, right, bottom, top" "$anvil" "$b/contact_unknown_slave.prm"
expect "contact: unknown Slave boundary (--set)" "--set.*'Contact/sliding/Slave'.*'nowhere'.*left, right, bottom, top" "$anvil" "$c" --set "Contact/sliding/Slave=nowhere"
expect "contact: empty Slave" "--set: 'Contact/sliding/Slave' is empty: expected the name of a boundary" "$anvil" "$c" --set "Contact/sliding/Slave="
expect "contact: Master neither boundary nor tool" "--set: 'Contact/sliding/Master' = 'ceiling' is neither a boundary \(left, right, bottom, top\) nor a tool" "$anvil" "$c" --set "Contact/sliding/Master=ceiling"
# Self-contact (Master = Slave) is allowed; lists that share part of their boundaries are not.
expect "contact: Master shares part of Slave" "--set: 'Contact/sliding/Master' = 'bottom, left' shares boundaries with Slave = 'bottom': expected the same list" "$anvil" "$c" --set "Contact/sliding/Master=bottom, left"
expect "contact: unknown boundary in a list" "--set: 'Contact/sliding/Slave' = 'bottom, nowhere': 'nowhere' is not a boundary of the mesh \(left, right, bottom, top\)" "$anvil" "$c" --set "Contact/sliding/Slave=bottom, nowhere"
expect "contact: boundary twice in a list" "--set: 'Contact/sliding/Slave' = 'bottom, bottom' names a boundary twice" "$anvil" "$c" --set "Contact/sliding/Slave=bottom, bottom"
expect "contact: zero normal penalty" "--set: 'Contact/sliding/Penalty normal' must be > 0" "$anvil" "$c" --set "Contact/sliding/Penalty normal=0"
expect "contact: negative normal penalty" "--set 'Contact/sliding/Penalty normal=-1'.*Double 0" "$anvil" "$c" --set "Contact/sliding/Penalty normal=-1"
expect "contact: friction without tangential penalty" "--set: 'Contact/sliding/Penalty tangent' must be > 0 when there is friction" "$anvil" "$c" --set "Contact/sliding/Penalty tangent=0"
expect "contact: dynamic friction above static" "--set: 'Contact/sliding/Dynamic friction coefficient' must not exceed the static" "$anvil" "$c" --set "Contact/sliding/Dynamic friction coefficient=0.5"
expect "contact: 3D tool in 2D" "--set: 'Contact/floor/Type' is cylinder, a 3D tool: in 2D use arc, circle, plane or polyline" "$anvil" "$c" --set "Contact/floor/Type=cylinder"
expect "contact: 2D tool in 3D" "--set: 'Contact/floor/Type' is circle, a 2D tool: in 3D use cylinder, plane or sphere" "$anvil" "$c" "${d3[@]}" --set "Contact/floor/Type=circle"
expect "contact: invalid tool Motion" "--set: 'Contact/floor/Motion' has an invalid expression '-t\*'.*muparser formula in t" "$anvil" "$c" --set "Contact/floor/Motion=0, -t*"
expect "contact: tool Motion with too few components" "--set: 'Contact/floor/Motion' = '0' has 1 components: expected 2" "$anvil" "$c" --set "Contact/floor/Motion=0"
expect "contact: two pairs with the same name" "--set: 'Contact/Pairs' uses the name 'sliding' twice.*distinct names" "$anvil" "$c" --set "Contact/Pairs=sliding, sliding"
expect "contact: pair named like a body" "--set: 'Contact/Pairs' uses the name 'block' .*bodies need distinct names" "$anvil" "$c" --set "Contact/Pairs=block"
expect "contact: Two-pass with a tool" "--set: 'Contact/sliding/Two-pass' is true but the Master is a rigid tool" "$anvil" "$c" --set "Contact/sliding/Two-pass=true"
# Registered parts: an unknown name lists what is registered.
n="$src/prm/necking_bar.prm"
expect "unknown material model" "--set 'Bodies/body/Material/Model=J3'.*hypoelastic.*J2.*Perzyna" "$anvil" "$n" --set "Bodies/body/Material/Model=J3"
expect "unknown hardening law" "--set 'Bodies/body/Material/Hardening/Model=ludwik'.*Selection [a-z |-]*voce[a-z |-]*\]" "$anvil" "$n" --set "Bodies/body/Material/Hardening/Model=ludwik"
expect "unknown softening law" "--set 'Bodies/body/Material/Hardening/Thermal softening/Model=arrhenius'.*johnson-cook.*linear.*none.*table" "$anvil" "$n" --set "Bodies/body/Material/Hardening/Thermal softening/Model=arrhenius"
expect "unknown tool shape" "--set 'Contact/floor/Type=cone'.*arc.circle.plane.polyline.cylinder.sphere" "$anvil" "$c" --set "Contact/floor/Type=cone"
# Temperature-dependent data (issue 13): tables and every tabulated value checked.
m="Bodies/body/Material"
expect "unsorted temperature table" "--set: '$m/Elasticity/Modulus temperature factor/Table' is not increasing in its first column \(293 then 250\)" "$anvil" "$n" --set "$m/Elasticity/Modulus temperature factor/Model=table" --set "$m/Elasticity/Modulus temperature factor/Table=293 : 1, 250 : 0.9"
expect "temperature table too short" "--set: '$m/Elasticity/Thermal expansion temperature factor/Table' needs at least two 'x : y' pairs" "$anvil" "$n" --set "$m/Elasticity/Thermal expansion temperature factor/Model=table" --set "$m/Elasticity/Thermal expansion temperature factor/Table=293 : 1"
expect "negative eta at a tabulated T" "--set: '$m/Viscosity/Eta/Table' gives eta = -1 at T = 700 K: expected eta >= 0 at every temperature" "$anvil" "$n" --set "$m/Model=Perzyna" --set "$m/Viscosity/Eta/Model=table" --set "$m/Viscosity/Eta/Table=293 : 10, 500 : 2, 700 : -1"
expect "m = 0 at a tabulated T" "--set: '$m/Viscosity/m/Table' gives m = 0 at T = 500 K: expected m > 0 at every temperature" "$anvil" "$n" --set "$m/Model=Perzyna" --set "$m/Viscosity/m/Model=table" --set "$m/Viscosity/m/Table=293 : 3, 500 : 0"
expect "yield stress <= 0 inside the table" "--set: '$m/Hardening/Yield stress of T/Table' gives the initial yield stress = 0 at T = 800 K: expected the initial yield stress > 0" "$anvil" "$n" --set "$m/Hardening/Model=temperature linear" --set "$m/Hardening/Yield stress of T/Model=table" --set "$m/Hardening/Yield stress of T/Table=293 : 200, 600 : 50, 800 : 0"
expect "negative eta inside an expression's Range" "--set: '$m/Viscosity/Eta/Expression' gives eta = -0.0394 at T = 794.97 K: expected eta >= 0" "$anvil" "$n" --set "$m/Model=Perzyna" --set "$m/Viscosity/Eta/Model=expression" --set "$m/Viscosity/Eta/Expression=10 - 0.02*(T-293)" --set "$m/Viscosity/Eta/Range=293, 1000"
exit $fail

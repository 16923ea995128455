#!/usr/bin/env bash
# Issue 17, "what still gets through": each hostile input is refused with exit
# status 2 and one line on stderr naming the file (or --set) and the parameter,
# without deal.II's banner, and never a signal or a hang. Most are refused by
# --check (before any work); those that only a run can meet (a formula that is
# finite at t = 0 but not later, a yield stress that softening drives to zero)
# are refused at the first evaluation that produces them, naming entry and time.
# Prints one line per case and the count.
set -u
anvil="$1"; src="$2"
work="$(mktemp -d)"; cd "$work"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 DEAL_II_NUM_THREADS=1
fail=0; n=0
expect() { # description, regex the message must match, command...
  local what="$1" regex="$2"; shift 2
  n=$((n + 1))
  local out err status
  err=$(timeout 300 "$@" 2>&1 >"$work/stdout"); status=$?
  out=$(cat "$work/stdout")
  # Under mpirun, mpirun adds its own lines about a process's exit status.
  [ "$1" = mpirun ] && err=$(printf '%s\n' "$err" | grep "^anvil:")
  local lines; lines=$(printf '%s\n' "$err" | grep -c .)
  local shown="${err:0:400}"
  if [ $status -eq 2 ] && [ "$lines" -eq 1 ] && printf '%s' "$err" | grep -Eq -- "$regex" &&
     ! printf '%s%s' "$out" "$err" | grep -Eq -- "An error occurred in line|\+-----|Total wallclock"; then
    echo "PASS  $what: $shown"
  else
    echo "FAIL  $what (exit $status, $lines line(s)): $shown"; fail=1
  fi
}
P="$src/prm"; M="Bodies/body/Material"
o=(--set "Output/Directory=$work/out" --set "Output/Verbosity=quiet")

# Probes (checked against the mesh --check builds).
expect "probe outside the mesh" "--set: 'Output/Probes' puts the probe 'tip' at \(1e\+06 1e\+06\), outside the mesh" \
  "$anvil" "$P/cantilever.prm" --check "${o[@]}" --set "Output/Probes=tip: 1e6, 1e6"
expect "probe named twice" "--set: 'Output/Probes' names the probe 'tip' twice" \
  "$anvil" "$P/cantilever.prm" --check "${o[@]}" --set "Output/Probes=tip: 10, 0.5; tip: 5, 0.5"
expect "probe at NaN" "'Output/Probes' item 'tip: nan, 0.5': 'nan' is not a finite number" \
  "$anvil" "$P/cantilever.prm" --check "${o[@]}" --set "Output/Probes=tip: nan, 0.5"

# Output directories (already refused before this issue's work: verified here).
long=$(printf 'd%.0s' $(seq 1 5000))
expect "over-long output directory" "--set: 'Output/Directory' = 'd+ \[\.\.\. [0-9]+ characters left out \.\.\.\].*cannot be created \(File name too long\)" \
  "$anvil" "$P/cantilever.prm" --check --set "Output/Directory=$long"
expect "unwritable output directory" "'Output/Directory' = '/proc/anvil_cannot' cannot be created" \
  "$anvil" "$P/cantilever.prm" --set "Output/Directory=/proc/anvil_cannot"
expect "unwritable output directory, 2 processes" "'Output/Directory' = '/proc/anvil_cannot' cannot be created" \
  mpirun -np 2 --oversubscribe "$anvil" "$P/cantilever.prm" --set "Output/Directory=/proc/anvil_cannot"
expect "maximum time step below the first (verified)" "'Time/Maximum time step' = 0.01 s must not be smaller than Time step" \
  "$anvil" "$P/necking_bar.prm" --check "${o[@]}" --set "Time/Maximum time step=0.01"

# 100 000 characters where a name or a number goes: no signal 11.
python3 - "$P/cantilever.prm" <<'EOF'
import sys
text = open(sys.argv[1]).read()
open("long_name.prm", "w").write(text.replace("set End time", "set End time" + "x" * 100000, 1))
open("long_number.prm", "w").write(text.replace("set End time  = 1", "set End time  = " + "9" * 100000, 1))
open("long_value.prm", "w").write(text.replace("set Pressure     = top: 20*t", "set Pressure     = top: " + "t+" * 50000 + "t", 1))
EOF
expect "100 000-character entry name" "long_name.prm:[0-9]+: .*characters left out" \
  "$anvil" long_name.prm --check "${o[@]}"
expect "100 000-digit number" "long_number.prm:[0-9]+: .*End time" "$anvil" long_number.prm --check "${o[@]}"
expect "100 000-character entry name (--set)" "--set '.*characters left out" \
  "$anvil" "$P/cantilever.prm" --check "${o[@]}" --set "Time/$(printf 'x%.0s' $(seq 1 100000))=1"

# Corrupt gmsh files: --check reads the mesh the run will use.
python3 - "$P/meshes/two_squares.msh" <<'EOF'
import sys
text = open(sys.argv[1]).read()
L = text.split("\n")
n0, e0 = L.index("$Nodes") + 2, L.index("$Elements") + 2
q = [k for k in range(e0, L.index("$EndElements")) if L[k].split()[1] == "3"][0]
def write(name, lines): open(name, "w").write("\n".join(lines))
M = list(L); f = M[n0 + 10].split(); f[1] = "nan"; M[n0 + 10] = " ".join(f); write("nan.msh", M)
M = list(L); f = M[q].split(); f[-1] = f[-3]; M[q] = " ".join(f); write("repeated.msh", M)
M = list(L); del M[n0 + 5]; write("missing.msh", M)
M = list(L); M[e0 - 1] = str(int(M[e0 - 1]) - 2); write("count.msh", M)
open("truncated.msh", "w").write(text[:int(len(text) * 0.8)])
M = list(L); M[n0 - 1] = "99999999999"; write("huge.msh", M)
M = list(L); f = M[q].split(); f[-1] = "99999"; M[q] = " ".join(f); write("unknown.msh", M)
EOF
mesh=("$anvil" "$P/bimaterial_gmsh.prm" --check "${o[@]}" --set)
expect "gmsh: NaN coordinate" "'Geometry/Mesh file' \('.*nan.msh'\) node 11 .* has the coordinate 'nan'" "${mesh[@]}" "Geometry/Mesh file=$work/nan.msh"
expect "gmsh: quad with a repeated node" "'Geometry/Mesh file' \('.*repeated.msh'\) element [0-9]+ repeats node" "${mesh[@]}" "Geometry/Mesh file=$work/repeated.msh"
expect "gmsh: missing node" "'Geometry/Mesh file' .*declares '45' nodes but does not list that many" "${mesh[@]}" "Geometry/Mesh file=$work/missing.msh"
expect "gmsh: wrong element count" "'Geometry/Mesh file' .*elements but does not list that many|is malformed" "${mesh[@]}" "Geometry/Mesh file=$work/count.msh"
expect "gmsh: truncated elements" "'Geometry/Mesh file' .*declares '56' elements but does not list that many" "${mesh[@]}" "Geometry/Mesh file=$work/truncated.msh"
expect "gmsh: huge node count" "'Geometry/Mesh file' .*declares '99999999999' nodes" "${mesh[@]}" "Geometry/Mesh file=$work/huge.msh"
expect "gmsh: unknown node" "'Geometry/Mesh file' .*refers to node 99999, which \\\$Nodes does not list" "${mesh[@]}" "Geometry/Mesh file=$work/unknown.msh"

# Geometry that cannot be run.
expect "Global refinements = 70000" "'Geometry/Global refinements' = 70000 would make about 10\^42146 cells .* GB \(estimate" \
  "$anvil" "$P/cantilever.prm" --check "${o[@]}" --set "Geometry/Global refinements=70000"
expect "Transformation inverting cells" "'Geometry/Transformation' makes a mesh where the cell at .* negative Jacobian" \
  "$anvil" "$P/cantilever.prm" --check "${o[@]}" --set "Geometry/Transformation=-x, y"

# Materials and temperatures.
expect "Young's modulus 1e308" "'$M/Elasticity/Young's modulus' = 1e\+308 MPa gives the P-wave modulus" \
  "$anvil" "$P/necking_bar.prm" --check "${o[@]}" --set "$M/Elasticity/Young's modulus=1e308"
expect "subnormal Poisson's ratio 1e-308" "'Poisson's ratio' = 1e-308: not representable as a double" \
  "$anvil" "$P/necking_bar.prm" --check "${o[@]}" --set "$M/Elasticity/Poisson's ratio=1e-308"
expect "reference temperature 0 K" "'$M/Elasticity/Reference temperature' = 0 K: expected an absolute temperature > 0 K" \
  "$anvil" "$P/necking_bar_thermal.prm" --check "${o[@]}" --set "$M/Elasticity/Reference temperature=0"
expect "softening reference temperature 0 K" "'$M/Hardening/Thermal softening/Reference temperature' = 0.* K: expected an absolute" \
  "$anvil" "$P/necking_bar_thermal.prm" --check "${o[@]}" --set "$M/Hardening/Thermal softening/Reference temperature=0"
expect "mechanics temperature 0 K" "'Mechanics/Temperature' = 0.* K: expected an absolute temperature > 0 K" \
  "$anvil" "$P/necking_bar.prm" --check "${o[@]}" --set "Mechanics/Temperature=0"
bar=("$anvil" "$P/necking_bar_thermal.prm" --check "${o[@]}")
# Absolute temperatures at every node, refused by --check (before the mesh's
# matrices, the output, any step): constant, a formula that crosses 0 K inside
# the bar (26.667 mm long: 293 - 30 y = -507 K at its top), one that is
# infinite on the axis x = 0, and the same scene when run.
expect "initial temperature -5 K" "'Heat/Initial temperature' = '-5' gives -5 K at a node" \
  "${bar[@]}" --set "Heat/Initial temperature=-5"
expect "initial temperature 293 - 30 y, < 0 K for y > 9.77 mm" "'Heat/Initial temperature' = '293 - 30\*y' gives -[0-9.]+ K at a node \(0 (9\.[89]|[1-2][0-9])[0-9.]*\)" \
  "${bar[@]}" --set "Heat/Initial temperature=293 - 30*y"
expect "initial temperature 293/x, infinite on the axis" "'Heat/Initial temperature' = '293/x' evaluates to \+inf at x = 0" \
  "${bar[@]}" --set "Heat/Initial temperature=293/x"
expect "initial temperature -5 K (run)" "'Heat/Initial temperature' = '-5' gives -5 K at a node" \
  "$anvil" "$P/necking_bar_thermal.prm" "${o[@]}" --set "Heat/Initial temperature=-5" --set "Time/End time=0.1"
# A prescribed temperature is absolute too: 293 - 400 t is 293 - 1.24e6 = -1239707 K at the
# forming scene's end (3100 s); 293/y is infinite on the y = 0 edge.
expect "prescribed temperature < 0 K at the end" "'Physics/Prescribed temperature' = '293 - 400\*t' gives -1.23971e\+06 K at a node .* at t = 3100 s: expected an absolute temperature > 0 K" \
  "$anvil" "$P/quarter_cylinder_forming.prm" --check "${o[@]}" --set "Physics/Prescribed temperature=293 - 400*t"
expect "prescribed temperature 293/y, infinite on an edge" "'Physics/Prescribed temperature' = '293/y' evaluates to \+inf at" \
  "$anvil" "$P/quarter_cylinder_forming.prm" --check "${o[@]}" --set "Physics/Prescribed temperature=293/y"
# Yield stresses that are certainly gone at the scene's temperatures, refused
# by --check. Linear softening (seed eq. 35) vanishes at T_ref + 1/omega =
# 293 + 1/0.002 = 793 K: an initial temperature of 800 K, or a boundary held at
# 293 + 200 t K (1293 K at the end time 5 s), is beyond it. The law
# 'temperature linear' with sigma_0(T) = 450 (1 - 0.01 (T - 293)) vanishes at
# 393 K; with sigma_0(T) = 450 - 5 (T - 293) (an expression, no limit it can
# name) the yield stress at 400 K is 450 - 535 = -85 MPa.
S="$M/Hardening/Thermal softening/Softening coefficient"
expect "softening: initial temperature past T_ref + 1/omega" "'$S' makes the yield stress vanish at T >= 793 K \(T_ref \+ 1/omega = 293 \+ 1/0.002\), but .*'Heat/Initial temperature' = '800' gives T = 800 K at a node" \
  "${bar[@]}" --set "Heat/Initial temperature=800"
expect "softening: boundary temperature past T_ref + 1/omega at the end" "'$S' makes the yield stress vanish at T >= 793 K .*, but .*'Heat/Boundary conditions/Temperature' on 'top' at t = 5 s gives T = 1293 K at a node" \
  "${bar[@]}" --set "Heat/Boundary conditions/Temperature=top: 293 + 200*t"
TL=(--set "$M/Hardening/Model=temperature linear" --set "$M/Hardening/Softened parameters=none"
    --set "$M/Hardening/Hardening modulus of T/Value=100" --set "Heat/Initial temperature=400")
expect "temperature linear: sigma_0(T) linear, gone at 393 K" "'$M/Hardening/Yield stress of T/Softening' makes the yield stress vanish at T >= 393 K \(T_ref \+ 1/omega = 293 \+ 1/0.01\), but .* gives T = 400 K" \
  "${bar[@]}" "${TL[@]}" --set "$M/Hardening/Yield stress of T/Model=linear" \
  --set "$M/Hardening/Yield stress of T/Value=450" --set "$M/Hardening/Yield stress of T/Softening=0.01"
expect "temperature linear: sigma_0(T) an expression, -85 MPa at 400 K" "'$M/Hardening' gives the yield stress -85 MPa <= 0 at T = 400 K and plastic strain 0, but .*'Heat/Initial temperature' = '400' gives T = 400 K" \
  "${bar[@]}" "${TL[@]}" --set "$M/Hardening/Yield stress of T/Model=expression" \
  --set "$M/Hardening/Yield stress of T/Expression=450 - 5*(T - 293)"
expect "mechanics only: Mechanics/Temperature past T_ref + 1/omega" "'$S' makes the yield stress vanish at T >= 793 K .*, but .*'Mechanics/Temperature' = 900 K gives T = 900 K" \
  "$anvil" "$P/necking_bar.prm" --check "${o[@]}" --set "$M/Hardening/Thermal softening/Model=linear" --set "$S=0.002" --set "Mechanics/Temperature=900"
# Formulas that are finite at t = 0 but not later: an input error at the first
# evaluation that gives NaN or inf, naming the entry, the point and the time.
expect "pressure 1/(t - 0.1)" "--set: 'Boundary conditions/Pressure' = '20\*t/\(t-0.1\)' evaluates to \+inf at .*t = 0.1: expected a finite value" \
  "$anvil" "$P/cantilever.prm" "${o[@]}" --set "Boundary conditions/Pressure=top: 20*t/(t-0.1)"
expect "displacement sqrt(-t)" "'Boundary conditions/Displacement' = 'sqrt\(-t\)' evaluates to NaN at x = 0, y = 0, t = 0.05" \
  "$anvil" "$P/cantilever.prm" "${o[@]}" --set "Boundary conditions/Displacement=left: ux = sqrt(-t), uy = 0"
# (A prescribed boundary temperature is evaluated at t = 0 and at the end time
# by --check: this one is refused before any work, at t = 1 s.)
expect "boundary temperature log(0.2 - t)" "'Heat/Boundary conditions/Temperature' = 'log\(0.2-t\)\+393' evaluates to (NaN|-inf) at .*t = (0.2|1):" \
  "$anvil" "$P/heat_half_space.prm" "${o[@]}" --set "Heat/Boundary conditions/Temperature=left: log(0.2-t)+393"
# Finite at t = 0 and at the end (1 s), NaN for 0.3 < t < 0.6: met by the run.
expect "boundary temperature NaN between 0.3 s and 0.6 s" "'Heat/Boundary conditions/Temperature' = '393 \+ sqrt\(\(t-0.3\)\*\(t-0.6\)\)' evaluates to NaN at .*t = 0\.[3-6]" \
  "$anvil" "$P/heat_half_space.prm" "${o[@]}" --set "Heat/Boundary conditions/Temperature=left: 393 + sqrt((t-0.3)*(t-0.6))"
expect "tool motion sqrt(-t)" "'Contact/floor/Motion' = 'if\(t>0, sqrt\(-t\), 0\)' evaluates to NaN at t = " \
  "$anvil" "$src/tests/contact_block.prm" "${o[@]}" --set "Contact/floor/Motion=0, if(t>0, sqrt(-t), 0)"
# The pressure is infinite on part of the boundary only: on 2 processes, the
# one that meets it tells the other; both stop with the one message.
expect "pressure infinite on one process's part, 2 processes" "'Boundary conditions/Pressure' = 'if\(x>8, t/0, 20\*t\)' evaluates to \+inf at x = [89]" \
  mpirun -np 2 --oversubscribe "$anvil" "$P/cantilever.prm" "${o[@]}" --set "Boundary conditions/Pressure=top: if(x>8, t/0, 20*t)"

# Checkpoints: garbage and huge counts refused at parse (verified here).
"$anvil" "$P/cantilever.prm" --set "Output/Directory=$work/ck" --set "Output/Verbosity=quiet" --set "Time/End time=0.05" > /dev/null
state="$work/ck/checkpoint/state.txt"; cp "$state" state.good
sed -i 's/^output.fields.pvd [0-9]*/output.fields.pvd 99999999999999/' "$state"
expect "checkpoint: huge record count" "state.txt: the checkpoint entry 'fields.pvd' is damaged \(99999999999999 records" \
  "$anvil" "$P/cantilever.prm" "${o[@]}" --set "Output/Restart from=$work/ck/checkpoint"
cp state.good "$state"; sed -i 's/^steps .*/steps 99999999999999999999999/' "$state"
expect "checkpoint: huge step count" "'Output/Restart from'.*the checkpoint entry 'steps' = '99999999999999999999999' is not a count" \
  "$anvil" "$P/cantilever.prm" "${o[@]}" --set "Output/Restart from=$work/ck/checkpoint"
head -c 3000 /dev/urandom > "$state"
expect "checkpoint: garbage state file" "'Output/Restart from'" \
  "$anvil" "$P/cantilever.prm" "${o[@]}" --set "Output/Restart from=$work/ck/checkpoint"
cp state.good "$state"; printf 'garbage' >> "$work/ck/checkpoint/mesh_fixed.data"
expect "checkpoint: damaged mesh file" "'Output/Restart from'.*its file 'mesh_fixed.data' is not the one written with it" \
  "$anvil" "$P/cantilever.prm" "${o[@]}" --set "Output/Restart from=$work/ck/checkpoint"
# A fault on one process while the other waits in the next step's collective
# calls: run.cc's end_with() gives it 10 s to arrive, then MPI_Abort ends the
# job with the one message and status 3 (not a hang, not a signal).
n=$((n + 1)); start=$(date +%s)
err=$(ANVIL_RANK_FAULT=1:3 timeout 120 mpirun -np 2 --oversubscribe "$anvil" "$P/cantilever.prm" "${o[@]}" 2>&1 >/dev/null); status=$?
elapsed=$(( $(date +%s) - start )); mine=$(printf '%s\n' "$err" | grep "^anvil:")
if [ $status -eq 3 ] && [ "$(printf '%s\n' "$mine" | grep -c .)" -eq 1 ] &&
   printf '%s' "$mine" | grep -q "^anvil: simulation stopped: injected fault on process 1 after step 3"; then
  echo "PASS  fault on one process, the other in a collective: exit 3 after ${elapsed} s: $mine"
else
  echo "FAIL  fault on one process, the other in a collective (exit $status after ${elapsed} s): ${err:0:600}"; fail=1
fi

# A softening that the run's own heating drives past its vanishing temperature
# (omega = 0.05 /K: T_ref + 1/omega = 293 + 20 = 313 K; the bar heats past it)
# is stopped at the first converged state beyond it, not in the trial
# iterates: exit 3, one line naming the point's temperature (>= 313 K), the
# time and the entry, the results and a checkpoint written; on 2 processes the
# same line (the hottest point, whatever the partition).
soft=("$P/necking_bar_thermal.prm" --set "Output/Verbosity=quiet" --set "Physics/Coupling=isothermal split"
      --set "$S=0.05")
stopped=""
for np in 1 2; do
  n=$((n + 1))
  run=("$anvil" "${soft[@]}" --set "Output/Directory=$work/soft$np")
  [ $np -eq 2 ] && run=(mpirun -np 2 --oversubscribe "${run[@]}")
  err=$(timeout 300 "${run[@]}" 2>&1 >/dev/null); status=$?
  mine=$(printf '%s\n' "$err" | grep "^anvil:")
  line=$(printf '%s' "$mine" | sed 's/ (last converged state.*//')
  if [ $status -eq 3 ] && [ "$(printf '%s\n' "$mine" | grep -c .)" -eq 1 ] &&
     printf '%s' "$mine" | grep -Eq "^anvil: simulation stopped: the yield stress vanished at t = [0-9.e+-]+ s: a converged state has T = (31[3-9]|3[2-9][0-9]|[4-9][0-9][0-9])(\.[0-9]+)? K at a point .*'$S' makes the yield stress vanish at T >= 313 K \(T_ref \+ 1/omega = 293 \+ 1/0.05\)" &&
     [ -f "$work/soft$np/checkpoint/state.txt" ] && grep -q 'yield stress vanished' "$work/soft$np/summary.json" &&
     { [ $np -eq 1 ] || [ "$line" = "$stopped" ]; }; then
    echo "PASS  softening past T_ref + 1/omega in the run, $np process(es): exit 3, checkpoint and summary written: $mine"
  else
    echo "FAIL  softening past T_ref + 1/omega in the run, $np process(es) (exit $status): ${err:0:600}"
    [ $np -eq 2 ] && echo "      1 process said: $stopped"; fail=1
  fi
  [ $np -eq 1 ] && stopped="$line"
done
echo "$n hostile inputs tried"
rm -rf "$work"
exit $fail

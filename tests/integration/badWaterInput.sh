#!/bin/bash
# Each broken water or block input must stop floatingBlockDEM with a non-zero
# exit (not a crash) and a message naming the file and the entry.
# usage: badWaterInput.sh CASE WORKDIR APP
set -uo pipefail
case_dir="$1"; work="$2"; app="$3"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
passed=0; failed=0

check() {   # name, file, sed expression, expected text in the message
    local name="$1" file="$2" edit="$3" expected="$4"
    rm -rf "$work/$name"; mkdir -p "$work/$name"
    cp -r "$case_dir/constant" "$case_dir/system" "$case_dir/DEM" "$work/$name/"
    if [ "$edit" = delete ]; then rm "$work/$name/$file"; else sed -i -e "$edit" "$work/$name/$file"; fi
    out=$(mpirun -np 1 "$app" -case "$work/$name" 2>&1); rc=$?
    if [ $rc -ne 0 ] && [ $rc -lt 128 ] && grep -qF -- "$expected" <<<"$out"; then
        echo "ok   $name: $(grep -F -- "$expected" <<<"$out" | head -1 | sed 's/^ *//')"
        passed=$((passed + 1))
    else
        echo "FAIL $name (exit $rc), expected '$expected' in:"; echo "$out" | tail -5
        failed=$((failed + 1))
    fi
}

check unknownLevel      constant/couplingProperties 's/^waterLevel[^;]*;/waterLevel still;/' "couplingProperties: entry 'waterLevel'"
check noWater           constant/couplingProperties 's/^waterLevel[^;]*;/waterLevel none;/'  "couplingProperties: entry 'waterLevel'"
check negativeDensity   constant/couplingProperties 's/rho[^;]*;/rho -1000;/'               "couplingProperties: entry 'hydrostatic.rho'"
check unknownDrag       constant/couplingProperties 's/drag[^;]*;/drag Stokes;/'            "couplingProperties: entry 'hydrostatic.drag'"
check negativeAddedMass constant/couplingProperties 's/addedMassCoefficient[^;]*;/addedMassCoefficient -1;/' "hydrostatic.addedMassCoefficient"
check sidewaysGravity   constant/g                  's/^value[^;]*;/value (9.81 0 0);/'     "g: entry 'value'"
check missingGravity    constant/g                  delete                                "needs gravity"
check heavyIce          constant/iceProperties      's/density[^;]*;/density 1100;/'        "material.density"
check badLattice        constant/blockProperties    's/lattice[^;]*;/lattice random;/'      "block.lattice"
check badSphereCount    constant/blockProperties    's/spheres[^;]*;/spheres (8 6 0.5);/'   "block.spheres"

echo "$passed passed, $failed failed"
[ $failed -eq 0 ]

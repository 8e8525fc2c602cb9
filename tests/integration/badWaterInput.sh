#!/bin/bash
# Each broken water or block input must stop floatingBlockDEM with a non-zero
# exit (not a crash) and a message naming the file and the entry.
# usage: badWaterInput.sh CASE WORKDIR APP
set -uo pipefail
case_dir="$1"; work="$2"; app="$3"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
source "$(dirname "${BASH_SOURCE[0]}")/refusalChecks.sh"

check() {   # name, file, sed expression (or "delete"), expected text in the message
    copy_broken_case "$1" "$2" "$3"
    expect_refusal "$1" "$4"
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
# Inertia scaling is refused: the heave (its period grows with sqrt(s)) is the floating block's answer.
check inertiaScaling    constant/blockProperties    's/^block$/inertiaScaling 10;\nblock/'  "10 is not allowed here (only 1): the floating block's answer is its motion (the heave"

report

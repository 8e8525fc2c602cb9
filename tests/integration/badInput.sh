#!/bin/bash
# Each broken input must stop iceBeamDEM with a non-zero exit (not a crash)
# and a message naming the entry.
# usage: badInput.sh CASE WORKDIR APP
set -uo pipefail
case_dir="$1"; work="$2"; app="$3"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
source "$(dirname "${BASH_SOURCE[0]}")/refusalChecks.sh"

check() {   # name, file, sed expression (or "delete"), expected text in the message
    copy_broken_case "$1" "$2" "$3"
    expect_refusal "$1" "$4" -particles 100
}

check negativeModulus   constant/iceProperties  '0,/youngsModulus .*;/s//youngsModulus -5.4e8;/' "material.youngsModulus"
check missingEntry      constant/iceProperties  '/breakN/d'                    "bondFamilies.ice.breakN"
check distFactorBelow1  constant/iceProperties  's/distFactor .*;/distFactor 0.9;/' "bondFamilies.ice.distFactor"
check unknownDamping    constant/iceProperties  's/model .*hysteretic;/model springy;/' "damping.model"
check unsafeTimeStep    constant/iceProperties  's/factor .*;/factor 1.5;/'    "timeStep.factor"
check badParticleCount  constant/beamProperties 's/particles .*;/particles abc;/' "packing.particles"
check tooFewBondSlots   constant/iceProperties  's/maxBondsPerParticle .*;/maxBondsPerParticle 2;/' "maxBondsPerParticle"
check unreachablePacking constant/beamProperties 's/solidFraction .*;/solidFraction 0.73;/' "packing.solidFraction"
check unknownVtkFormat  system/controlDict      's/vtkFormat  *binary;/vtkFormat legacy;/' "system/controlDict: entry 'vtkFormat': line 21: unknown value 'legacy'; allowed: ascii binary"
check missingFile       constant/beamProperties delete                         "beamProperties"
check inertiaBelowOne   constant/beamProperties 's/^inertiaScaling .*;/inertiaScaling 0.5;/' "beamProperties: entry 'inertiaScaling'"
check inertiaTooLarge   constant/beamProperties 's/^inertiaScaling .*;/inertiaScaling 1e6;/' "beamProperties: entry 'inertiaScaling'"
check inertiaNotANumber constant/beamProperties 's/^inertiaScaling .*;/inertiaScaling fast;/' "beamProperties: entry 'inertiaScaling'"
check missingScript     DEM/in.levelIceBeam     delete                         "in.levelIceBeam"

report

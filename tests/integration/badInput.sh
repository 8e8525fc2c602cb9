#!/bin/bash
# Each broken input must stop iceBeamDEM with a non-zero exit (not a crash)
# and a message naming the entry.
# usage: badInput.sh CASE WORKDIR APP
set -uo pipefail
case_dir="$1"; work="$2"; app="$3"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
passed=0; failed=0

check() {   # name, file, sed expression, expected text in the message
    local name="$1" file="$2" edit="$3" expected="$4"
    rm -rf "$work/$name"; mkdir -p "$work/$name"
    cp -r "$case_dir/constant" "$case_dir/system" "$case_dir/DEM" "$work/$name/"
    if [ "$edit" = delete ]; then rm "$work/$name/$file"; else sed -i -e "$edit" "$work/$name/$file"; fi
    out=$(mpirun -np 1 "$app" -case "$work/$name" -particles 100 2>&1); rc=$?
    if [ $rc -ne 0 ] && [ $rc -lt 128 ] && grep -qF -- "$expected" <<<"$out"; then
        echo "ok   $name: $(grep -F -- "$expected" <<<"$out" | head -1 | sed 's/^ *//')"
        passed=$((passed + 1))
    else
        echo "FAIL $name (exit $rc), expected '$expected' in:"; echo "$out" | tail -5
        failed=$((failed + 1))
    fi
}

check negativeModulus   constant/iceProperties  '0,/youngsModulus .*;/s//youngsModulus -5.4e8;/' "material.youngsModulus"
check missingEntry      constant/iceProperties  '/breakN/d'                    "bondFamilies.ice.breakN"
check distFactorBelow1  constant/iceProperties  's/distFactor .*;/distFactor 0.9;/' "bondFamilies.ice.distFactor"
check unknownDamping    constant/iceProperties  's/model .*hysteretic;/model springy;/' "damping.model"
check unsafeTimeStep    constant/iceProperties  's/factor .*;/factor 1.5;/'    "timeStep.factor"
check badParticleCount  constant/beamProperties 's/particles .*;/particles abc;/' "packing.particles"
check tooFewBondSlots   constant/iceProperties  's/maxBondsPerParticle .*;/maxBondsPerParticle 2;/' "maxBondsPerParticle"
check missingFile       constant/beamProperties delete                         "beamProperties"
check missingScript     DEM/in.levelIceBeam     delete                         "in.levelIceBeam"

echo "$passed passed, $failed failed"
[ $failed -eq 0 ]

#!/bin/bash
# iceFoam refuses bad couplingProperties with a clear message and a non-zero exit.
# Usage: badInput.sh CASE_SOURCE WORK_DIR ICEFOAM [bondedIce|vof]
#   bondedIce: the case has constant/iceProperties (cases/floatingBlock/cfd);
#   checks the bonded ice model's inputs instead.
#   vof: the case is at the vof level (cases/floatingBlock/vof, iceInterFoam);
#   checks its inputs and limits.
# A change rm:FILE removes the file from the copy.
set -uo pipefail
src=$1 work=$2 app=$3 checks=${4:-coupling}
failures=0
source "$(dirname "${BASH_SOURCE[0]}")/../../bin/caseCommon.sh"   # copy_case_common

# expectRefusal NAME EXPECTED_MESSAGE FILE:ENTRY=VALUE...
expectRefusal() {
    local name=$1 expected=$2
    shift 2
    local dir="$work/$name"
    rm -rf "$dir"
    mkdir -p "$dir"
    cp -r "$src/0" "$src/constant" "$src/system" "$src/DEM" "$dir/"
    copy_case_common "$dir"
    for change in "$@"; do
        local file=${change%%:*} setting=${change#*:}
        if [ "$file" = rm ]; then
            rm -f "$dir/$setting"
            continue
        fi
        foamDictionary -entry "${setting%%=*}" -set "${setting#*=}" "$dir/$file" > /dev/null
    done
    blockMesh -case "$dir" > "$dir/log.blockMesh" 2>&1
    if [ -n "${ranks:-}" ]; then    # decomposed as system/decomposeParDict says
        foamDictionary -entry numberOfSubdomains -set "$ranks" "$dir/system/decomposeParDict" > /dev/null
        decomposePar -case "$dir" > "$dir/log.decomposePar" 2>&1
        OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 \
            mpirun -np "$ranks" --oversubscribe "$app" -case "$dir" -parallel > "$dir/log.iceFoam" 2>&1
    else
        "$app" -case "$dir" > "$dir/log.iceFoam" 2>&1
    fi
    local rc=$?
    if [ $rc -eq 0 ]; then
        echo "FAIL $name: accepted (exit 0)"; failures=$((failures + 1))
    elif ! grep -qF -- "$expected" "$dir/log.iceFoam"; then
        echo "FAIL $name: exit $rc without '$expected'; log ends:"; tail -15 "$dir/log.iceFoam"
        failures=$((failures + 1))
    else
        echo "ok   $name: exit $rc, says: $(grep -F -m1 -- "$expected" "$dir/log.iceFoam" | sed 's/^ *//')"
    fi
}

props=constant/couplingProperties
if [ "$checks" = vof ]; then
    control=system/controlDict
    expectRefusal noAlphaWater "hydrodynamics vof needs the water fraction" "rm:0/alpha.water"
    expectRefusal surfaceAboveMesh "entry 'vof/initialLevel' is 0.5 m: the water surface must lie inside the mesh" \
        "$props:vof/initialLevel=0.5"
    expectRefusal surfaceBelowMesh "entry 'vof/initialLevel' is -0.7 m" "$props:vof/initialLevel=-0.7"
    expectRefusal cfdLevel "entry 'hydrodynamics' is 'cfd': iceInterFoam" "$props:hydrodynamics=cfd"
    expectRefusal flatSurfaceEntry "entry 'waterLevel' is the flat surface of level cfd" "$props:waterLevel=0"
    expectRefusal flowCourantAbove "entry 'maxCo' is 0.8" "$control:maxCo=0.8"
    expectRefusal interfaceCourantAbove "entry 'maxAlphaCo' is 0.6" "$control:maxAlphaCo=0.6"
    expectRefusal courantExceeded "above entry 'maxCo' = 0.001" "$control:maxCo=0.001"
    expectRefusal cellsSmallerThanParticles "is smaller than the largest particle" \
        "$props:demVariables/radius=0.08" "$props:demVariables/demTimeStep=1e-4"
    expectRefusal cellsThinnerThanARadius "less than the largest particle's radius" \
        "system/blockMeshDict:blocks=(hex (0 1 2 3 4 5 6 7) (8 6 36) simpleGrading (1 1 1))"
    expectRefusal gravitySideways "needs gravity along -z" "constant/g:value=(0 -9.81 0)"
    expectRefusal heaveCouplingTooLong "holds each particle's buoyancy for too long" \
        "$props:couplingInterval=2800" "$control:deltaT=0.07"
    expectRefusal badWaveDamping "vof/waveDamping" "$props:vof/waveDamping/width=0"
    ranks=2 expectRefusal columnCutByRanks "the decomposition cuts a vertical column of cells" \
        "system/decomposeParDict:coeffs/n=(1 1 2)"
    exit $failures
fi
if [ "$checks" = bondedIce ]; then
    ice=constant/iceProperties
    expectRefusal iceDensityNotScript "constant/iceProperties material.density is 900" \
        "$ice:material/density=900"
    expectRefusal unknownDampingModel "entry 'damping.model'" "$ice:damping/model=sticky"
    expectRefusal negativeModulus "youngsModulus" "$ice:bondFamilies/ice/youngsModulus=-1"
    expectRefusal demStepTooLong "is above the bonded pack's stability limit" "$props:demVariables/demTimeStep=1e-3"
    exit $failures
fi
expectRefusal unknownDragModel "Unknown dragModel type Stokes" "$props:dragModel=Stokes"
expectRefusal unknownFluidFraction "Unknown fluidFractionModel type voronoi" "$props:fluidFractionModel=voronoi"
expectRefusal unknownMomentumCoupling "Unknown momentumCoupling type implicit" "$props:momentumCoupling=implicit"
expectRefusal fluidStepNotDividing "does not divide" "system/controlDict:deltaT=3e-4"
expectRefusal adjustableFluidStep "adjustTimeStep" "system/controlDict:adjustTimeStep=yes"
expectRefusal particleOutsideMesh "is outside the fluid mesh" "$props:demVariables/zMax=0.3" "$props:demVariables/z0=0.2"
expectRefusal hydrostaticLevel "entry 'hydrodynamics'" "$props:hydrodynamics=hydrostatic"
expectRefusal vofLevel "level vof (a moving free surface) runs in iceInterFoam" "$props:hydrodynamics=vof"
expectRefusal badAlphaMin "alphaMin" "$props:alphaMin=1.5"
expectRefusal zeroCouplingInterval "a whole number >= 1" "$props:couplingInterval=0"
exit $failures

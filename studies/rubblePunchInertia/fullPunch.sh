#!/bin/bash
# The case's whole cuboid punch (100 mm at the laboratory's 5 mm/s) with inertia scaling FACTOR on
# 2 ranks, from the published run's assembled ridge (cases/rubblePunch/runs/cuboid/DEM/ridge.h5,
# made by the case's ./Allrun), the kinetic-energy limit lifted so that the ratio is measured, not
# refused. Writes cases/rubblePunch/runs/cuboid-inertiaFACTOR and copies its summary and force curve
# into results/fullPunch_inertiaFACTOR_2ranks_*.
#
# usage: studies/rubblePunchInertia/fullPunch.sh FACTOR      (10: about 4 minutes on 2 cores)
set -euo pipefail
factor=${1:?usage: fullPunch.sh FACTOR}
[[ "$factor" =~ ^[1-9][0-9]*$ ]] || { echo "fullPunch.sh: FACTOR must be a whole number >= 1, not '$factor'" >&2; exit 2; }
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
top=$(cd "$here/../.." && pwd)
source "$top/bin/caseCommon.sh"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
case=$top/cases/rubblePunch
published=$case/runs/cuboid
[ -f "$published/DEM/ridge.h5" ] || { echo "fullPunch.sh: no $published/DEM/ridge.h5: run cases/rubblePunch/Allrun -keels cuboid first" >&2; exit 1; }

run=$case/runs/cuboid-inertia$factor
rm -rf "$run"; mkdir -p "$run/DEM"
cp -r "$published/constant" "$published/system" "$run"/
cp "$published/DEM/ridge.h5" "$published/DEM/in.ridge" "$published/DEM/platen.stl" "$run/DEM/"
# the factor, and the limit lifted (measured, not refused), with iceCases' dictionary editing
PYTHONPATH="$top/postProcessing" /usr/bin/python3 -c "import sys, iceCases
run, factor = sys.argv[1:]
iceCases.set_entry(run + '/constant/ridgeProperties', 'test.inertiaScaling', factor)
iceCases.add_entry(run + '/system/controlDict', 'maxKineticToWorkRatio', '1e30')" "$run" "$factor"
/usr/bin/time -v -o "$run/time.txt" mpirun -np 2 "$top/build/demModels/ridgeDEM" -case "$run" -stage all \
    > "$run/log.ridgeDEM" 2>&1
cp "$run/postProcessing/summary.json" "$here/results/fullPunch_inertia${factor}_2ranks_summary.json"
cp "$run/postProcessing/platenForce.csv" "$here/results/fullPunch_inertia${factor}_2ranks_platenForce.csv"
grep -E "Elapsed|Maximum resident" "$run/time.txt"
tail -1 "$run/log.ridgeDEM"

#!/bin/bash
# Runs a copy of an iceFoam case on 1 or more ranks (decomposePar first).
# Usage: runIceFoam.sh ICEFOAM CASE_SOURCE COPY RANKS [FILE:ENTRY=VALUE ...]
#   entries in foamDictionary scope syntax, e.g. system/controlDict:endTime=0.5
set -euo pipefail
app=$1 src=$2 dest=$3 np=$4
shift 4
rm -rf "$dest"
mkdir -p "$dest"
cp -r "$src/0" "$src/constant" "$src/system" "$src/DEM" "$dest/"
source "$(dirname "${BASH_SOURCE[0]}")/../../bin/caseCommon.sh"
copy_case_common "$dest"
for change in "$@"; do
    file=${change%%:*} setting=${change#*:}
    foamDictionary -entry "${setting%%=*}" -set "${setting#*=}" "$dest/$file" > /dev/null
done
blockMesh -case "$dest" > "$dest/log.blockMesh" 2>&1 || { cat "$dest/log.blockMesh"; exit 1; }
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_mpi_yield_when_idle=${OMPI_MCA_mpi_yield_when_idle:-1}
if [ "$np" -gt 1 ]; then
    foamDictionary -entry numberOfSubdomains -set "$np" "$dest/system/decomposeParDict" > /dev/null
    decomposePar -case "$dest" > "$dest/log.decomposePar" 2>&1 || { cat "$dest/log.decomposePar"; exit 1; }
    mpirun -np "$np" --oversubscribe "$app" -case "$dest" -parallel > "$dest/log.iceFoam" 2>&1 \
        || { tail -30 "$dest/log.iceFoam"; exit 1; }
else
    "$app" -case "$dest" > "$dest/log.iceFoam" 2>&1 || { tail -30 "$dest/log.iceFoam"; exit 1; }
fi
echo "runIceFoam: $dest on $np rank(s) done"

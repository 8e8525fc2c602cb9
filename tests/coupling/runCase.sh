#!/bin/bash
# Runs a shortened copy of a coupling case through its own Allrun.
# Usage: runCase.sh CASE_SOURCE COPY RANKS ENDTIME [FILE:ENTRY=VALUE ...]
#   e.g. constant/couplingProperties:demVariables/z0=0.075 (foamDictionary scope syntax)
set -euo pipefail
src=$1 dest=$2 np=$3 endTime=$4
shift 4
rm -rf "$dest"
mkdir -p "$dest"
cp -r "$src/0" "$src/constant" "$src/system" "$src/DEM" "$dest/"
source "$(dirname "${BASH_SOURCE[0]}")/../../bin/caseCommon.sh"
copy_case_common "$dest"
foamDictionary -entry endTime -set "$endTime" "$dest/system/controlDict" > /dev/null
for change in "$@"; do
    file=${change%%:*} setting=${change#*:}
    foamDictionary -entry "${setting%%=*}" -set "${setting#*=}" "$dest/$file" > /dev/null
done
"$src/Allrun" -case "$dest" -np "$np"

#!/bin/bash
# Copies a beam case's inputs into a work folder and runs iceBeamDEM there.
# usage: runBeamCase.sh CASE WORKDIR NP APP [app options...]
set -euo pipefail
case_dir="$1"; work="$2"; np="$3"; app="$4"; shift 4
rm -rf "$work"
mkdir -p "$work"
cp -r "$case_dir/constant" "$case_dir/system" "$case_dir/DEM" "$work/"
rm -f "$work/DEM/packing.data" "$work/DEM/platen.stl"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
mpirun -np "$np" --oversubscribe "$app" -case "$work" "$@" > "$work/log.iceBeamDEM" 2>&1 \
    || { tail -30 "$work/log.iceBeamDEM"; exit 1; }
tail -3 "$work/log.iceBeamDEM"

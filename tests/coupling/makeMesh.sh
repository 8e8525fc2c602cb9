#!/bin/bash
# Copies an OpenFOAM case to a fresh folder and runs blockMesh in it (ctest fixture).
set -euo pipefail
src=$1 dest=$2
rm -rf "$dest"
mkdir -p "$dest/constant"
cp -r "$src/system" "$dest/"
blockMesh -case "$dest" > "$dest/log.blockMesh" 2>&1 || { cat "$dest/log.blockMesh"; exit 1; }

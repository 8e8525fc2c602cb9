#!/bin/bash
# Each broken constant/bendingProperties must stop threePointBendingDEM with a
# non-zero exit (not a crash) and a message naming the entry.
# usage: badBendingInput.sh CASE WORKDIR APP
set -uo pipefail
case_dir="$1"; work="$2"; app="$3"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
source "$(dirname "${BASH_SOURCE[0]}")/refusalChecks.sh"

check() {   # name, sed expression on constant/bendingProperties, expected text, extra options
    local name="$1" edit="$2" expected="$3"; shift 3
    copy_broken_case "$name" constant/bendingProperties "$edit"
    expect_refusal "$name" "$expected" "$@"
}

check missingThickness  '/thickness /d'                       "beam.thickness"
check zeroThickness     's/thickness [^;]*;/thickness 0;/'        "beam.thickness"
check negativeThickness 's/thickness [^;]*;/thickness -0.1;/'     "beam.thickness"
check spanBeyondBeam    's/span [^;]*;/span 3.2;/'                "supports.span"
check missingSpan       '/span /d'                             "supports.span"
check badDiameter       's/particleDiameter [^;]*;/particleDiameter abc;/' "packing.particleDiameter"
check particleTooBig    's/ particleDiameter [^;]*;/ particleDiameter 0.12;/' "packing.particleDiameter"
check unknownEntry      's/span /spam 1; span /'               "supports.spam"
check badOption         ''                                     "-thickness" -thickness -0.1
check inertiaBelowOne   's/^inertiaScaling [^;]*;/inertiaScaling 0.5;/' "bendingProperties: entry 'inertiaScaling'"

report

#!/bin/bash
# The program's time-step limit against the measured instability of the level-ice beam at 1,200
# particles (studies/stabilityMap: unstable from factor 0.375-0.40 damped, 0.45 undamped; the
# program's limit 0.333):
#   insideLimit      factor 0.33, a little inside the limit: runs to its end (exit 0, a summary)
#   pastMeasured     factor 0.45, past the measured instability: refused before it starts,
#                    naming timeStep.factor
#   unsafeRunsStops  factor 0.6 with timeStep.refuseUnsafe no (stability studies): it runs, says it
#                    is above the limit, and the blow-up check stops it as unstable
# usage: timeStepLimits.sh CASE WORKDIR APP
set -uo pipefail
case_dir="$1"; work="$2"; app="$3"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
source "$(dirname "${BASH_SOURCE[0]}")/refusalChecks.sh"

copy_broken_case insideLimit constant/iceProperties 's/factor .*;/factor 0.33;/'
sed -i 's/^writeInterval .*;/writeInterval 10;/' "$work/insideLimit/case/system/controlDict"   # no frames
if mpirun -np 1 "$app" -case "$work/insideLimit/case" -particles 1200 > "$work/insideLimit/log" 2>&1 \
    && [ -s "$work/insideLimit/case/postProcessing/summary.json" ]; then
    echo "ok   insideLimit: factor 0.33 ran to its end"; passed=$((passed + 1))
else
    echo "FAIL insideLimit: factor 0.33 did not run to its end:"; tail -5 "$work/insideLimit/log"; failed=$((failed + 1))
fi

copy_broken_case pastMeasured constant/iceProperties 's/factor .*;/factor 0.45;/'
expect_refusal pastMeasured "timeStep.factor" -particles 1200

copy_broken_case unsafeRunsStops constant/iceProperties 's/factor .*;/factor 0.6; refuseUnsafe no;/'
out=$(mpirun -np 1 "$app" -case "$work/unsafeRunsStops/case" -particles 1200 2>&1); rc=$?
if [ $rc -ne 0 ] && [ $rc -lt 128 ] && grep -qF "ABOVE THE LIMIT" <<<"$out" && grep -qF "the run is unstable" <<<"$out"; then
    echo "ok   unsafeRunsStops: $(grep -F "the run is unstable" <<<"$out" | head -1 | sed 's/^ *//' | cut -c1-120)"
    passed=$((passed + 1))
else
    echo "FAIL unsafeRunsStops (exit $rc):"; echo "$out" | tail -5; failed=$((failed + 1))
fi

report

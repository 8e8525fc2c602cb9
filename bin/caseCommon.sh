# Sourced by Allruns and test scripts that copy a case (or its constant/) to
# another folder. Case dictionaries `#include "../../common/..."`, relative to
# the file, so a copy at DIR/name needs cases/common at DIR/common; the same
# rule as copy_common in postProcessing/iceCases.py.

caseCommonSource="$(cd "$(dirname "${BASH_SOURCE[0]}")/../cases/common" && pwd)"

# An input error ends every rank with the application's own message and status 1; without this
# mpirun adds a banner about "1 process returned a non-zero exit code" that reads like a crash.
export OMPI_MCA_orte_execute_quiet=1

# Open MPI binds the ranks of every mpirun to cores from core 0 on, unaware of other jobs: two
# 1-rank runs side by side (a study's -jobs 2, two keels) both ran on core 0, each at 0.44 of its
# speed alone (studies/sceneSpeed). Unbound, the kernel spreads them over the cores.
export OMPI_MCA_hwloc_base_binding_policy=${OMPI_MCA_hwloc_base_binding_policy:-none}

# copy_case_common COPY: cases/common copied to COPY/../common (COPY is the
# copied case folder, which must exist); nothing to do when that is cases/common.
copy_case_common() {
    local target
    target="$(cd "$1/.." && pwd)/common"
    [ "$target" = "$caseCommonSource" ] && return 0
    mkdir -p "$target"
    cp -r "$caseCommonSource/." "$target/"
}

# included_files FILE: the files FILE's #include / #includeIfPresent lines
# name, resolved against FILE's folder, one a line (those that exist).
included_files() {
    local dir name
    dir="$(dirname "$1")"
    sed -n 's/^[[:space:]]*#include\(IfPresent\)\{0,1\}[[:space:]]*"\([^"]*\)".*/\2/p' "$1" |
    while IFS= read -r name; do
        case "$name" in /*) ;; *) name="$dir/$name" ;; esac
        [ -f "$name" ] && echo "$name"
    done
}

# result_complete DIR: whether DIR holds a finished run's result set: a
# postProcessing/summary.json that does not say "complete": false (a run in the
# making, killed or stopped by an error). The same as finished() in iceCases.py.
result_complete() {
    [ -f "$1/postProcessing/summary.json" ] && ! grep -q '"complete": false' "$1/postProcessing/summary.json"
}

# ranks_dict NP N: a copy of system/decomposeParDict (of the case in the current
# folder) for NP subdomains, coeffs n = N, written to postProcessing/decomposeParDict;
# prints its absolute path, for decomposePar's and the solver's -decomposeParDict.
# A run never edits the case's own dictionaries (tracked files; foamDictionary
# -set also rewrites their header).
ranks_dict() {
    local dict="$PWD/postProcessing/decomposeParDict"
    mkdir -p postProcessing
    cp system/decomposeParDict "$dict"
    foamDictionary -entry numberOfSubdomains -set "$1" "$dict" > /dev/null
    foamDictionary -entry coeffs/n -set "$2" "$dict" > /dev/null
    echo "$dict"
}

# publish_results RESULTS RUN ... -- FILE:NAME ...: the explicit step (./Allrun
# -publish) that copies finished runs' files into the committed RESULTS folder:
# each FILE (a path as given) as RESULTS/NAME, each written to a temporary file
# there and renamed. Refuses, changing nothing, unless every RUN holds a complete
# result set (result_complete) and every FILE exists. Other files in RESULTS stay.
publish_results() {
    local results="$1" run pair
    shift
    while [ $# -gt 0 ] && [ "$1" != -- ]; do
        result_complete "$1" || {
            echo "publish: $1 holds no finished run ($1/postProcessing/summary.json missing or \"complete\": false); nothing published" >&2
            return 1
        }
        shift
    done
    shift
    for pair; do
        [ -f "${pair%:*}" ] || { echo "publish: ${pair%:*} missing; nothing published" >&2; return 1; }
    done
    mkdir -p "$results"
    for pair; do
        cp "${pair%:*}" "$results/.${pair##*:}.publishing"
        mv -f "$results/.${pair##*:}.publishing" "$results/${pair##*:}"
        echo "published $results/${pair##*:}"
    done
}

# summary_value DIR KEY: the value of "KEY" (a number or a string) in
# DIR/postProcessing/summary.json, empty if there is none.
summary_value() {
    [ -f "$1/postProcessing/summary.json" ] || return 0
    sed -n 's/^ *"'"$2"'": "\{0,1\}\([^",]*\)"\{0,1\},\{0,1\}$/\1/p' "$1/postProcessing/summary.json" | head -1
}

# keel_file KEEL: the saved stage of the rubble case KEEL that a ridge reads as its
# keel (keel.settledRubble): DEM/compacted.h5 where its rubbleProperties compacts
# (compaction.method plates), else DEM/settled.h5.
keel_file() {
    if grep -Eq '^[[:space:]]*method[[:space:]]+plates[[:space:]]*;' "$1/constant/rubbleProperties"; then
        echo "$1/DEM/compacted.h5"
    else
        echo "$1/DEM/settled.h5"
    fi
}

# inputs_fingerprint PATH... -- WORD...: a digest of the files under each PATH and of the
# files their dictionaries #include, recursively (names and contents;
# postProcessing/inputFiles.py), and of the WORDs (a run's own settings). A run folder
# records the fingerprint of what it was made from (RUN/madeFrom), so that a finished
# run, or a checkpoint, is never reused once the case, what it includes or the keel
# changed; a calibration in ../common that the case does not include leaves it alone.
inputs_fingerprint() {
    local paths=()
    while [ $# -gt 0 ] && [ "$1" != -- ]; do paths+=("$1"); shift; done
    shift
    local lister
    lister="$(dirname "${BASH_SOURCE[0]}")/../postProcessing/inputFiles.py"
    { /usr/bin/python3 "$lister" "${paths[@]}" | tr '\n' '\0' | xargs -0 sha256sum; echo "$*"; } \
        | sha256sum | cut -c1-16
}

# reuse_run RUN FINGERPRINT RESUMING: what to do with an existing run folder RUN for
# inputs of FINGERPRINT: prints "done" (finished from these inputs), "resume" (not
# finished, these inputs, RESUMING yes) or "make" (anything else; a run of other
# inputs is removed with a message, and resuming it is refused).
reuse_run() {
    local run="$1" made="$2" resuming="$3"
    [ -d "$run" ] || { echo make; return; }
    if [ "$(cat "$run/madeFrom" 2>/dev/null)" != "$made" ]; then
        if [ "$resuming" = yes ]; then
            echo "$run was made from other inputs (the case's dictionaries, ../common or the keel changed since): it cannot be resumed; run without -resume" >&2
            exit 1
        fi
        echo "$run was made from other inputs (the case's dictionaries, ../common or the keel changed since): made again" >&2
        rm -rf "$run"
        echo make; return
    fi
    if result_complete "$run"; then echo done
    elif [ "$resuming" = yes ]; then echo resume
    else echo make
    fi
}

# build_keel KEEL RESUME COMMAND...: the keel KEEL settled (COMMAND -case KEEL
# -stage settle [RESUME], log KEEL/log.rubbleDEM) unless DEM/settled.h5 is there,
# then compacted (-stage compact, log KEEL/log.compact) where it compacts, unless
# DEM/compacted.h5 is there. COMMAND runs rubbleDEM (mpirun ... rubbleDEM);
# RESUME is -resume or "".
build_keel() {
    local keel="$1" resume="$2"
    shift 2
    if [ ! -f "$keel/DEM/settled.h5" ]; then
        echo "Settling the keel $keel (rubbleDEM -stage settle); log in $keel/log.rubbleDEM"
        "$@" -case "$keel" -stage settle $resume > "$keel/log.rubbleDEM" 2>&1 \
            || { tail -20 "$keel/log.rubbleDEM" >&2; return 1; }
        grep -E "^(Settled|NOT at rest)" "$keel/log.rubbleDEM" || true
    fi
    if [ "$(keel_file "$keel")" = "$keel/DEM/compacted.h5" ] && [ ! -f "$keel/DEM/compacted.h5" ]; then
        echo "Compacting the keel $keel (rubbleDEM -stage compact); log in $keel/log.compact"
        "$@" -case "$keel" -stage compact > "$keel/log.compact" 2>&1 \
            || { tail -20 "$keel/log.compact" >&2; return 1; }
        grep "^Compacted" "$keel/log.compact" || true
    fi
}

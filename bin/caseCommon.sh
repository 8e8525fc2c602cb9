# Sourced by Allruns and test scripts that copy a case (or its constant/) to
# another folder. Case dictionaries `#include "../../common/..."`, relative to
# the file, so a copy at DIR/name needs cases/common at DIR/common; the same
# rule as copy_common in postProcessing/iceCases.py.

caseCommonSource="$(cd "$(dirname "${BASH_SOURCE[0]}")/../cases/common" && pwd)"

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
